// hairbsdf for GLSL: dFH11 f from a plan's N_p table (hairbsdf_deon_body.inc has the equations). The
// engine fills hb_deon_constants from hb_plan_shader_constants and the table from hb_plan_table or a
// table file (docs/engines.md gives both layouts). Needs GL_GOOGLE_include_directive (glslang) or the
// engine's own include. Before including this file, define how the table is read:
//     #define HB_DEON_TABLE(i) np_table[i]   // float i of hb_table_view.values (a storage buffer)
#ifndef HAIRBSDF_DEON_GLSL
#define HAIRBSDF_DEON_GLSL

#ifndef HB_CONST
#define HB_CONST const
#endif

#include "hairbsdf_deon_body.inc"

#endif
