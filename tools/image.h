/* Image files for the CLI: PFM (float RGB), PNG (8-bit sRGB, our own small encoder) and, when
 * OpenEXR is present, EXR (float RGB). */
#ifndef HB_IMAGE_H
#define HB_IMAGE_H

#include <stddef.h>
#include <stdint.h>

/* rgb: width * height * 3 floats, row 0 at the top. Return 0 on success, -1 on an I/O error. */
int image_write_pfm(const char *path, int width, int height, const float *rgb);
int image_write_png(const char *path, int width, int height, const uint8_t *rgb8);

/* OpenEXR float RGB (tools/image_exr.c), when built with OpenEXR (image_exr_available()):
 * write returns -2 without it; read returns a malloc'd width * height * 3 array or NULL. */
int image_exr_available(void);
int image_write_exr(const char *path, int width, int height, const float *rgb);
float *image_read_exr(const char *path, int *width, int *height);

/* Tone mapping for PNG: x / (1 + x) of exposure * f, then the sRGB transfer curve. */
void image_tonemap(size_t pixels, const float *rgb, float exposure, uint8_t *rgb8);

uint32_t image_crc32(const uint8_t *data, size_t n, uint32_t crc);
uint32_t image_adler32(const uint8_t *data, size_t n);

#endif
