// hairbsdf for GLSL: the dual-scattering term f_DS from a plan's table or from an engine-wide table
// (hairbsdf_dual_body.inc has the equations). For a plan's table the engine fills hb_dual_constants
// with the table's node count and density factors and uploads hb_dual_table_nodes' floats; for an
// engine-wide table, hb_dual_engine_constants with hb_dual_engine_constants' floats and uploads
// hb_dual_engine_nodes' (docs/multiple-scattering.md gives the layouts). Needs
// GL_GOOGLE_include_directive (glslang) or the engine's own include. Before including this file,
// define how either table is read:
//     #define HB_DUAL_TABLE(i) dual_table[i]          // float i of hb_dual_table_nodes (a storage buffer)
//     #define HB_DUAL_ENGINE_TABLE(i) engine_table[i] // float i of hb_dual_engine_nodes
#ifndef HAIRBSDF_DUAL_GLSL
#define HAIRBSDF_DUAL_GLSL

#ifndef HB_CONST
#define HB_CONST const
#endif

#include "hairbsdf_dual_body.inc"

#endif
