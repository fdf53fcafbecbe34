#version 450
// The shader test's GLSL kernel: hb_dual_f_default at sample k of SoA angles and fibre counts.
// Buffers (floats): 0 the table's node count, d_f, d_b and the sample count, 1 hb_dual_table_nodes,
// 2 theta_i, phi_i, theta_o, phi_o (n each), 3 f_DS r, g, b (n each), 4 the fibres n per sample.
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Params { float params[]; };
layout(std430, binding = 1) readonly buffer Table { float dual_table[]; };
layout(std430, binding = 2) readonly buffer Angles { float angles[]; };
layout(std430, binding = 3) writeonly buffer Out { float f_out[]; };
layout(std430, binding = 4) readonly buffer Fibres { float fibres[]; };
#define HB_DUAL_TABLE(i) dual_table[i]
#include "hairbsdf_dual.glsl"

void main()
{
    uint n = uint(params[3]), k = gl_GlobalInvocationID.x;
    if (k >= n)
        return;
    hb_dual_constants c;
    c.thetas = params[0], c.d_f = params[1], c.d_b = params[2];
    vec3 f = hb_dual_f_default(c, angles[k], angles[n + k], angles[2 * n + k], angles[3 * n + k], fibres[k]);
    f_out[k] = f.x;
    f_out[n + k] = f.y;
    f_out[2 * n + k] = f.z;
}
