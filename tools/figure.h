/* A lobe image as a labelled figure (tools/figure.c). */
#ifndef HB_FIGURE_H
#define HB_FIGURE_H

#include <stdint.h>

/* panels_rgb8: `panels` tone-mapped panels side by side, each panel_width x height, the lat-long
 * layout of hairbsdf dump (phi_o from -pi at the left, theta_o from pi/2 at the top). Returns a
 * malloc'd RGB image with the axes, their ticks in degrees, each panel's title (titles may be NULL),
 * the caption and the tone curve's colour scale for this exposure, and its size; NULL without memory. */
uint8_t *figure_frame(const uint8_t *panels_rgb8, int panel_width, int height, int panels, const char *caption,
                      const char *const *titles, double exposure, int *out_width, int *out_height);

#endif
