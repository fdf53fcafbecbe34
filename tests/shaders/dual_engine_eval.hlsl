// The shader test's HLSL kernel: the GLSL one's (dual_engine_eval.comp) buffers and work, through
// hairbsdf_dual.hlsl.
[[vk::binding(0)]] StructuredBuffer<float> params : register(t0);
[[vk::binding(1)]] StructuredBuffer<float> engine_table : register(t1);
[[vk::binding(2)]] StructuredBuffer<float> angles : register(t2);
[[vk::binding(3)]] RWStructuredBuffer<float> f_out : register(u3);
[[vk::binding(4)]] StructuredBuffer<float> fibres : register(t4);
#define HB_DUAL_ENGINE_TABLE(i) engine_table[i]
#include "hairbsdf_dual.hlsl"

[numthreads(64, 1, 1)]
void main(uint3 id : SV_DispatchThreadID)
{
    uint n = (uint)params[8], k = id.x;
    if (k >= n)
        return;
    hb_dual_engine_constants c;
    c.thetas = params[0];
    c.roughnesses = params[1];
    c.roughness_min = params[2];
    c.roughness_max = params[3];
    c.absorptions = params[4];
    c.absorption_span = params[5];
    c.d_f = params[6];
    c.d_b = params[7];
    float3 f = hb_dual_engine_f(c, angles[k], angles[n + k], angles[2 * n + k], angles[3 * n + k], params[9],
                                float3(params[10], params[11], params[12]), fibres[k], max(0.0, 1.0 - fibres[k]));
    f_out[k] = f.x;
    f_out[n + k] = f.y;
    f_out[2 * n + k] = f.z;
}
