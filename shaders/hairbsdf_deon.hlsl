// hairbsdf for HLSL: dFH11 f from a plan's N_p table (hairbsdf_deon_body.inc has the equations). The
// engine fills hb_deon_constants from hb_plan_shader_constants and the table from hb_plan_table or a
// table file (docs/engines.md gives both layouts). Before including this file, define how the table
// is read:
//     #define HB_DEON_TABLE(i) np_table[i]   // float i of hb_table_view.values (a StructuredBuffer<float>)
#ifndef HAIRBSDF_DEON_HLSL
#define HAIRBSDF_DEON_HLSL

#ifndef HB_CONST
#define HB_CONST static const
#define vec3 float3
#define vec4 float4
#endif

#include "hairbsdf_deon_body.inc"

#endif
