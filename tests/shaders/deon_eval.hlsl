// The shader test's HLSL kernel: the GLSL one's (deon_eval.comp) buffers and work, through
// hairbsdf_deon.hlsl.
[[vk::binding(0)]] StructuredBuffer<float> params : register(t0);
[[vk::binding(1)]] StructuredBuffer<float> np_table : register(t1);
[[vk::binding(2)]] StructuredBuffer<float> angles : register(t2);
[[vk::binding(3)]] RWStructuredBuffer<float> f_out : register(u3);
[[vk::binding(4)]] StructuredBuffer<float> sigma_a : register(t4);
#define HB_DEON_TABLE(i) np_table[i]
#include "hairbsdf_deon.hlsl"

[numthreads(64, 1, 1)]
void main(uint3 id : SV_DispatchThreadID)
{
    uint n = (uint)params[64], k = id.x;
    if (k >= n)
        return;
    hb_deon_constants c;
    c.grid = float4(params[0], params[1], params[2], params[3]);
    for (int s = 0; s < HB_DEON_MAX_SLOTS; s++)
        c.slot[s] = float4(params[4 + 4 * s], params[5 + 4 * s], params[6 + 4 * s], params[7 + 4 * s]);
    c.absorption = float4(params[40], params[41], params[42], params[43]);
    float3 f = params[65] > 0.5
                   ? hb_deon_f_strand(c, angles[k], angles[n + k], angles[2 * n + k], angles[3 * n + k],
                                      float3(sigma_a[k], sigma_a[n + k], sigma_a[2 * n + k]))
                   : hb_deon_f(c, angles[k], angles[n + k], angles[2 * n + k], angles[3 * n + k]);
    f_out[k] = f.x;
    f_out[n + k] = f.y;
    f_out[2 * n + k] = f.z;
}
