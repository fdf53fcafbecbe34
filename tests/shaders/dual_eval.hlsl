// The shader test's HLSL kernel: the GLSL one's (dual_eval.comp) buffers and work, through
// hairbsdf_dual.hlsl.
[[vk::binding(0)]] StructuredBuffer<float> params : register(t0);
[[vk::binding(1)]] StructuredBuffer<float> dual_table : register(t1);
[[vk::binding(2)]] StructuredBuffer<float> angles : register(t2);
[[vk::binding(3)]] RWStructuredBuffer<float> f_out : register(u3);
[[vk::binding(4)]] StructuredBuffer<float> fibres : register(t4);
#define HB_DUAL_TABLE(i) dual_table[i]
#include "hairbsdf_dual.hlsl"

[numthreads(64, 1, 1)]
void main(uint3 id : SV_DispatchThreadID)
{
    uint n = (uint)params[3], k = id.x;
    if (k >= n)
        return;
    hb_dual_constants c;
    c.thetas = params[0];
    c.d_f = params[1];
    c.d_b = params[2];
    float3 f = hb_dual_f_default(c, angles[k], angles[n + k], angles[2 * n + k], angles[3 * n + k], fibres[k]);
    f_out[k] = f.x;
    f_out[n + k] = f.y;
    f_out[2 * n + k] = f.z;
}
