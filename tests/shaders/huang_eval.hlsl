// The shader test's HLSL kernel for HHH22: the GLSL one's (huang_eval.comp) buffers and work,
// through hairbsdf_huang.hlsl.
[[vk::binding(0)]] StructuredBuffer<float> params : register(t0);
[[vk::binding(1)]] StructuredBuffer<float> tt_trt_table : register(t1);
[[vk::binding(2)]] StructuredBuffer<float> angles : register(t2);
[[vk::binding(3)]] RWStructuredBuffer<float> f_out : register(u3);
#define HB_HUANG_TABLE(i) tt_trt_table[i]
#include "hairbsdf_huang.hlsl"

float4 param4(int i) { return float4(params[i], params[i + 1], params[i + 2], params[i + 3]); }

[numthreads(64, 1, 1)]
void main(uint3 id : SV_DispatchThreadID)
{
    uint n = (uint)params[64], k = id.x;
    if (k >= n)
        return;
    hb_huang_constants c;
    c.lobes = param4(0), c.rough = param4(4), c.tilt = param4(8), c.grid = param4(12), c.axes = param4(16);
    c.warp = param4(20);
    float3 f = hb_huang_f(c, angles[k], angles[n + k], angles[2 * n + k], angles[3 * n + k]);
    f_out[k] = f.x;
    f_out[n + k] = f.y;
    f_out[2 * n + k] = f.z;
}
