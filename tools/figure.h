/* A lobe image, or any panels of pixels, as a labelled figure (tools/figure.c). */
#ifndef HB_FIGURE_H
#define HB_FIGURE_H

#include <stdint.h>

/* panels_rgb8: `panels` tone-mapped panels side by side, each panel_width x height, the lat-long
 * layout of hairbsdf dump (phi_o from -pi at the left, theta_o from pi/2 at the top). Returns a
 * malloc'd RGB image with the axes, their ticks in degrees, each panel's title (titles may be NULL),
 * the caption and the tone curve's colour scale for this exposure, and its size; NULL without memory. */
uint8_t *figure_frame(const uint8_t *panels_rgb8, int panel_width, int height, int panels, const char *caption,
                      const char *const *titles, double exposure, int *out_width, int *out_height);

/* The axes of a framed figure: each panel's x from x_left to x_right, the shared y from y_top to
 * y_bottom, each with five ticks labelled by value, and the name of what the colour scale shows. */
typedef struct figure_axes {
    const char *x_label, *y_label, *value_label; /* value_label: the colour scale's */
    double x_left, x_right, y_top, y_bottom;
} figure_axes;

/* figure_frame with the caller's axes (figure_frame's are phi_o and theta_o in degrees). */
uint8_t *figure_frame_axes(const uint8_t *panels_rgb8, int panel_width, int height, int panels, const char *caption,
                           const char *const *titles, const figure_axes *axes, double exposure, int *out_width,
                           int *out_height);

#endif
