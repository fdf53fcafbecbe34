#version 450
// The shader test's GLSL kernel for HHH22: hb_huang_f at sample k of SoA angles. Buffers (floats):
// 0 the constants (hb_plan_shader_constants, 64 floats) then the sample count, 1 the plan's TT/TRT
// table, 2 theta_i, phi_i, theta_o, phi_o (n each), 3 f_r, f_g, f_b (n each).
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Params { float params[]; };
layout(std430, binding = 1) readonly buffer Table { float tt_trt_table[]; };
layout(std430, binding = 2) readonly buffer Angles { float angles[]; };
layout(std430, binding = 3) writeonly buffer Out { float f_out[]; };
#define HB_HUANG_TABLE(i) tt_trt_table[i]
#include "hairbsdf_huang.glsl"

vec4 param4(int i) { return vec4(params[i], params[i + 1], params[i + 2], params[i + 3]); }

void main()
{
    uint n = uint(params[64]), k = gl_GlobalInvocationID.x;
    if (k >= n)
        return;
    hb_huang_constants c;
    c.lobes = param4(0), c.rough = param4(4), c.tilt = param4(8), c.grid = param4(12), c.axes = param4(16);
    c.warp = param4(20);
    vec3 f = hb_huang_f(c, angles[k], angles[n + k], angles[2 * n + k], angles[3 * n + k]);
    f_out[k] = f.x;
    f_out[n + k] = f.y;
    f_out[2 * n + k] = f.z;
}
