#version 450
// The shader test's GLSL kernel: hb_dual_engine_f at sample k, default visibility, for one fibre.
// Buffers (floats): 0 hb_dual_engine_constants' eight, the sample count, the fibre's roughness and
// sigma_a r, g, b; 1 hb_dual_engine_nodes; 2 theta_i, phi_i, theta_o, phi_o (n each); 3 f_DS r, g, b
// (n each); 4 the fibres n per sample.
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Params { float params[]; };
layout(std430, binding = 1) readonly buffer Table { float engine_table[]; };
layout(std430, binding = 2) readonly buffer Angles { float angles[]; };
layout(std430, binding = 3) writeonly buffer Out { float f_out[]; };
layout(std430, binding = 4) readonly buffer Fibres { float fibres[]; };
#define HB_DUAL_ENGINE_TABLE(i) engine_table[i]
#include "hairbsdf_dual.glsl"

void main()
{
    uint n = uint(params[8]), k = gl_GlobalInvocationID.x;
    if (k >= n)
        return;
    hb_dual_engine_constants c;
    c.thetas = params[0], c.roughnesses = params[1], c.roughness_min = params[2], c.roughness_max = params[3];
    c.absorptions = params[4], c.absorption_span = params[5], c.d_f = params[6], c.d_b = params[7];
    vec3 f = hb_dual_engine_f(c, angles[k], angles[n + k], angles[2 * n + k], angles[3 * n + k], params[9],
                              vec3(params[10], params[11], params[12]), fibres[k], max(0.0, 1.0 - fibres[k]));
    f_out[k] = f.x;
    f_out[n + k] = f.y;
    f_out[2 * n + k] = f.z;
}
