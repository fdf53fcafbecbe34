// hairbsdf for GLSL: HHH22 f on a circular fibre, its R lobe in closed form and its TT/TRT table
// (hairbsdf_huang_body.inc has the equations). The engine fills hb_huang_constants from
// hb_plan_shader_constants and the table from hb_plan_table or a table file (docs/engines.md).
// Before including this file, define how the table is read:
//     #define HB_HUANG_TABLE(i) tt_trt_table[i]   // float i of hb_table_view.values
#ifndef HAIRBSDF_HUANG_GLSL
#define HAIRBSDF_HUANG_GLSL

#ifndef HB_CONST
#define HB_CONST const
#endif
#define HB_ATAN2(y, x) atan(y, x)

#include "hairbsdf_huang_body.inc"

#endif
