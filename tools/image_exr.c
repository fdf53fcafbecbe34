/* OpenEXR float RGB through OpenEXR's C API (OpenEXRCore, Debian's libopenexr-dev), when the
 * build found it with pkg-config (HB_HAVE_OPENEXR); without it both calls return -2 and the
 * tool says so. One scanline part, channels R, G, B as 32-bit float, uncompressed: with OpenEXR
 * 3.1.5's ZIP and ZIPS, chunks that do not compress read back as garbage through this interleaved
 * binding (tests image_exr_round_trip and bake_files found it), NONE and PIZ read back exactly. */
#include <stdlib.h>
#include <string.h>

#include "image.h"

#ifdef HB_HAVE_OPENEXR
#include <openexr.h>

int image_exr_available(void) { return 1; }

/* Points each coding channel (named R, G or B) at its plane of the interleaved rgb rows. */
static void bind_channels(exr_coding_channel_info_t *channels, int count, const float *rgb_first_row,
                          int width)
{
    for (int c = 0; c < count; c++) {
        const char *name = channels[c].channel_name;
        int plane = name[0] == 'R' ? 0 : name[0] == 'G' ? 1 : 2;
        channels[c].user_bytes_per_element = 4;
        channels[c].user_data_type = EXR_PIXEL_FLOAT;
        channels[c].user_pixel_stride = 12;
        channels[c].user_line_stride = width * 12;
        channels[c].encode_from_ptr = (const uint8_t *)(rgb_first_row + plane);
    }
}

int image_write_exr(const char *path, int width, int height, const float *rgb)
{
    exr_context_t ctx;
    if (exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, NULL) != EXR_ERR_SUCCESS)
        return -1;
    int part, ok = 1;
    ok = ok && exr_add_part(ctx, "lobes", EXR_STORAGE_SCANLINE, &part) == EXR_ERR_SUCCESS;
    ok = ok && exr_initialize_required_attr_simple(ctx, part, width, height, EXR_COMPRESSION_NONE) == EXR_ERR_SUCCESS;
    static const char *const names[3] = { "R", "G", "B" };
    for (int c = 0; c < 3 && ok; c++)
        ok = exr_add_channel(ctx, part, names[c], EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1) ==
             EXR_ERR_SUCCESS;
    ok = ok && exr_write_header(ctx) == EXR_ERR_SUCCESS;
    int lines = 1;
    ok = ok && exr_get_scanlines_per_chunk(ctx, part, &lines) == EXR_ERR_SUCCESS;
    for (int y = 0; y < height && ok; y += lines) {
        exr_chunk_info_t chunk;
        exr_encode_pipeline_t encoder;
        memset(&encoder, 0, sizeof encoder);
        ok = exr_write_scanline_chunk_info(ctx, part, y, &chunk) == EXR_ERR_SUCCESS &&
             exr_encoding_initialize(ctx, part, &chunk, &encoder) == EXR_ERR_SUCCESS;
        if (!ok)
            break;
        bind_channels(encoder.channels, encoder.channel_count, rgb + (size_t)y * width * 3, width);
        ok = exr_encoding_choose_default_routines(ctx, part, &encoder) == EXR_ERR_SUCCESS &&
             exr_encoding_run(ctx, part, &encoder) == EXR_ERR_SUCCESS;
        exr_encoding_destroy(ctx, &encoder);
    }
    return exr_finish(&ctx) == EXR_ERR_SUCCESS && ok ? 0 : -1;
}

float *image_read_exr(const char *path, int *width, int *height)
{
    exr_context_t ctx;
    if (exr_start_read(&ctx, path, NULL) != EXR_ERR_SUCCESS)
        return NULL;
    exr_attr_box2i_t window;
    int lines = 1, ok = exr_get_data_window(ctx, 0, &window) == EXR_ERR_SUCCESS &&
                        exr_get_scanlines_per_chunk(ctx, 0, &lines) == EXR_ERR_SUCCESS;
    *width = window.max.x - window.min.x + 1;
    *height = window.max.y - window.min.y + 1;
    float *rgb = ok ? malloc((size_t)*width * (size_t)*height * 12) : NULL;
    for (int y = 0; rgb && y < *height && ok; y += lines) {
        exr_chunk_info_t chunk;
        exr_decode_pipeline_t decoder;
        memset(&decoder, 0, sizeof decoder);
        ok = exr_read_scanline_chunk_info(ctx, 0, window.min.y + y, &chunk) == EXR_ERR_SUCCESS &&
             exr_decoding_initialize(ctx, 0, &chunk, &decoder) == EXR_ERR_SUCCESS;
        if (!ok)
            break;
        /* the encoder's binding, used to decode: the same strides, written instead of read */
        bind_channels(decoder.channels, decoder.channel_count, rgb + (size_t)y * *width * 3, *width);
        ok = exr_decoding_choose_default_routines(ctx, 0, &decoder) == EXR_ERR_SUCCESS &&
             exr_decoding_run(ctx, 0, &decoder) == EXR_ERR_SUCCESS;
        exr_decoding_destroy(ctx, &decoder);
    }
    exr_finish(&ctx);
    if (!ok) {
        free(rgb);
        return NULL;
    }
    return rgb;
}

#else

int image_exr_available(void) { return 0; }

int image_write_exr(const char *path, int width, int height, const float *rgb)
{
    (void)path, (void)width, (void)height, (void)rgb;
    return -2;
}

float *image_read_exr(const char *path, int *width, int *height)
{
    (void)path, (void)width, (void)height;
    return NULL;
}

#endif
