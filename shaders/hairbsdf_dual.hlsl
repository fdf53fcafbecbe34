// hairbsdf for HLSL: the dual-scattering term f_DS from a plan's table (hairbsdf_dual_body.inc has
// the equations). The engine fills hb_dual_constants with the table's node count and density factors
// and uploads hb_dual_table_nodes' floats (docs/multiple-scattering.md gives the layout). Before
// including this file, define how the table is read:
//     #define HB_DUAL_TABLE(i) dual_table[i]   // float i of hb_dual_table_nodes (a StructuredBuffer<float>)
#ifndef HAIRBSDF_DUAL_HLSL
#define HAIRBSDF_DUAL_HLSL

#ifndef HB_CONST
#define HB_CONST static const
#define vec3 float3
#define vec4 float4
#endif

#include "hairbsdf_dual_body.inc"

#endif
