// hairbsdf for GLSL: the dual-scattering term f_DS from a plan's table (hairbsdf_dual_body.inc has
// the equations). The engine fills hb_dual_constants with the table's node count and density factors
// and uploads hb_dual_table_nodes' floats (docs/multiple-scattering.md gives the layout). Needs
// GL_GOOGLE_include_directive (glslang) or the engine's own include. Before including this file,
// define how the table is read:
//     #define HB_DUAL_TABLE(i) dual_table[i]   // float i of hb_dual_table_nodes (a storage buffer)
#ifndef HAIRBSDF_DUAL_GLSL
#define HAIRBSDF_DUAL_GLSL

#ifndef HB_CONST
#define HB_CONST const
#endif

#include "hairbsdf_dual_body.inc"

#endif
