#version 450
// The shader test's GLSL kernel: hb_deon_f at sample k of SoA angles, as an engine would call it.
// Buffers (floats): 0 the constants (hb_plan_shader_constants, 64 floats), the sample count and 1 for
// a colour table, 1 the plan's table, 2 theta_i, phi_i, theta_o, phi_o (n each), 3 f_r, f_g, f_b
// (n each), 4 each sample's sigma_a in R, G, B (n each; read with a colour table).
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Params { float params[]; };
layout(std430, binding = 1) readonly buffer Table { float np_table[]; };
layout(std430, binding = 2) readonly buffer Angles { float angles[]; };
layout(std430, binding = 3) writeonly buffer Out { float f_out[]; };
layout(std430, binding = 4) readonly buffer Absorption { float sigma_a[]; };
#define HB_DEON_TABLE(i) np_table[i]
#include "hairbsdf_deon.glsl"

void main()
{
    uint n = uint(params[64]), k = gl_GlobalInvocationID.x;
    if (k >= n)
        return;
    hb_deon_constants c;
    c.grid = vec4(params[0], params[1], params[2], params[3]);
    for (int s = 0; s < HB_DEON_MAX_SLOTS; s++)
        c.slot[s] = vec4(params[4 + 4 * s], params[5 + 4 * s], params[6 + 4 * s], params[7 + 4 * s]);
    c.absorption = vec4(params[40], params[41], params[42], params[43]);
    vec3 f = params[65] > 0.5
                 ? hb_deon_f_strand(c, angles[k], angles[n + k], angles[2 * n + k], angles[3 * n + k],
                                    vec3(sigma_a[k], sigma_a[n + k], sigma_a[2 * n + k]))
                 : hb_deon_f(c, angles[k], angles[n + k], angles[2 * n + k], angles[3 * n + k]);
    f_out[k] = f.x;
    f_out[n + k] = f.y;
    f_out[2 * n + k] = f.z;
}
