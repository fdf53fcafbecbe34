/* A lobe image as a figure a person can read: the tone-mapped panels framed by phi_o and theta_o
 * axes with ticks in degrees, a title per panel, a caption line, and the colour scale of the tone
 * curve with the values of f it maps. Text is drawn with a 5 x 7 pixel font of our own. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure.h"
#include "image.h"

/* Rows of each glyph, top first, bit 4 the leftmost of 5 columns. */
typedef struct glyph {
    char c;
    unsigned char rows[7];
} glyph;

static const glyph font[] = {
    { '0', { 0x0e, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0e } }, { '1', { 0x04, 0x0c, 0x04, 0x04, 0x04, 0x04, 0x0e } },
    { '2', { 0x0e, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1f } }, { '3', { 0x1f, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0e } },
    { '4', { 0x02, 0x06, 0x0a, 0x12, 0x1f, 0x02, 0x02 } }, { '5', { 0x1f, 0x10, 0x1e, 0x01, 0x01, 0x11, 0x0e } },
    { '6', { 0x06, 0x08, 0x10, 0x1e, 0x11, 0x11, 0x0e } }, { '7', { 0x1f, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08 } },
    { '8', { 0x0e, 0x11, 0x11, 0x0e, 0x11, 0x11, 0x0e } }, { '9', { 0x0e, 0x11, 0x11, 0x0f, 0x01, 0x02, 0x0c } },
    { 'A', { 0x0e, 0x11, 0x11, 0x1f, 0x11, 0x11, 0x11 } }, { 'B', { 0x1e, 0x11, 0x11, 0x1e, 0x11, 0x11, 0x1e } },
    { 'C', { 0x0e, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0e } }, { 'D', { 0x1c, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1c } },
    { 'E', { 0x1f, 0x10, 0x10, 0x1e, 0x10, 0x10, 0x1f } }, { 'F', { 0x1f, 0x10, 0x10, 0x1e, 0x10, 0x10, 0x10 } },
    { 'G', { 0x0e, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0f } }, { 'H', { 0x11, 0x11, 0x11, 0x1f, 0x11, 0x11, 0x11 } },
    { 'I', { 0x0e, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0e } }, { 'J', { 0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0c } },
    { 'K', { 0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11 } }, { 'L', { 0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1f } },
    { 'M', { 0x11, 0x1b, 0x15, 0x15, 0x11, 0x11, 0x11 } }, { 'N', { 0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11 } },
    { 'O', { 0x0e, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0e } }, { 'P', { 0x1e, 0x11, 0x11, 0x1e, 0x10, 0x10, 0x10 } },
    { 'Q', { 0x0e, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0d } }, { 'R', { 0x1e, 0x11, 0x11, 0x1e, 0x14, 0x12, 0x11 } },
    { 'S', { 0x0f, 0x10, 0x10, 0x0e, 0x01, 0x01, 0x1e } }, { 'T', { 0x1f, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04 } },
    { 'U', { 0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0e } }, { 'V', { 0x11, 0x11, 0x11, 0x11, 0x11, 0x0a, 0x04 } },
    { 'W', { 0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0a } }, { 'X', { 0x11, 0x11, 0x0a, 0x04, 0x0a, 0x11, 0x11 } },
    { 'Y', { 0x11, 0x11, 0x0a, 0x04, 0x04, 0x04, 0x04 } }, { 'Z', { 0x1f, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1f } },
    { '-', { 0x00, 0x00, 0x00, 0x1f, 0x00, 0x00, 0x00 } }, { '.', { 0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x0c } },
    { ',', { 0x00, 0x00, 0x00, 0x00, 0x0c, 0x04, 0x08 } }, { '=', { 0x00, 0x00, 0x1f, 0x00, 0x1f, 0x00, 0x00 } },
    { '(', { 0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02 } }, { ')', { 0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08 } },
    { '/', { 0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00 } }, { ':', { 0x00, 0x0c, 0x0c, 0x00, 0x0c, 0x0c, 0x00 } },
    { '_', { 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1f } }, { '+', { 0x00, 0x04, 0x04, 0x1f, 0x04, 0x04, 0x00 } },
    { '|', { 0x04, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04 } }, { '\'', { 0x04, 0x04, 0x08, 0x00, 0x00, 0x00, 0x00 } },
};

typedef struct canvas {
    uint8_t *rgb;
    int width, height, scale; /* scale: pixels per font pixel */
} canvas;

static void put(const canvas *c, int x, int y, uint8_t value)
{
    if (x >= 0 && y >= 0 && x < c->width && y < c->height)
        memset(c->rgb + ((size_t)y * (size_t)c->width + (size_t)x) * 3, value, 3);
}

static int text_width(const canvas *c, const char *s) { return (int)strlen(s) * 6 * c->scale - c->scale; }

/* Text in white on the dark frame, its top left corner at (x, y); letters in upper case. */
static void draw_text(const canvas *c, int x, int y, const char *s)
{
    for (; *s; s++, x += 6 * c->scale) {
        char ch = (char)toupper((unsigned char)*s);
        for (size_t g = 0; g < sizeof font / sizeof font[0]; g++) {
            if (font[g].c != ch)
                continue;
            for (int row = 0; row < 7; row++)
                for (int col = 0; col < 5; col++)
                    if (font[g].rows[row] >> (4 - col) & 1)
                        for (int dy = 0; dy < c->scale; dy++)
                            for (int dx = 0; dx < c->scale; dx++)
                                put(c, x + col * c->scale + dx, y + row * c->scale + dy, 230);
        }
    }
}

static void draw_tick_label(const canvas *c, int x, int y, const char *s, int centred)
{
    draw_text(c, centred ? x - text_width(c, s) / 2 : x - text_width(c, s), y, s);
}

/* f for a displayed value v of the tone curve v = exposure f / (1 + exposure f) (before sRGB). */
static double f_of_display(double v, double exposure) { return v / (1.0 - v) / exposure; }

uint8_t *figure_frame(const uint8_t *panels_rgb8, int panel_width, int height, int panels, const char *caption,
                      const char *const *titles, double exposure, int *out_width, int *out_height)
{
    static const figure_axes lat_long = { "PHI_O (DEGREES)", "THETA_O", "F", -180.0, 180.0, 90.0, -90.0 };
    return figure_frame_axes(panels_rgb8, panel_width, height, panels, caption, titles, &lat_long, exposure, out_width,
                             out_height);
}

uint8_t *figure_frame_axes(const uint8_t *panels_rgb8, int panel_width, int height, int panels, const char *caption,
                           const char *const *titles, const figure_axes *axes, double exposure, int *out_width,
                           int *out_height)
{
    /* rows above the panels: the caption, the panels' titles, the axis labels */
    int scale = panel_width >= 400 ? 2 : 1, line = 9 * scale, char_w = 6 * scale;
    int left = 5 * char_w, right = 2 * char_w + 10 * char_w, top = 3 * line + 2 * scale, bottom = 3 * line;
    int gap = 5 * char_w;
    canvas c = { NULL, left + panels * panel_width + (panels - 1) * gap + right, top + height + bottom, scale };
    c.rgb = calloc((size_t)c.width * (size_t)c.height * 3, 1);
    if (!c.rgb)
        return NULL;
    memset(c.rgb, 24, (size_t)c.width * (size_t)c.height * 3);
    draw_text(&c, 2 * scale, scale * 2, caption);
    for (int p = 0; p < panels; p++) {
        int x0 = left + p * (panel_width + gap);
        for (int y = 0; y < height; y++)
            memcpy(c.rgb + ((size_t)(top + y) * (size_t)c.width + (size_t)x0) * 3,
                   panels_rgb8 + ((size_t)y * (size_t)panels * (size_t)panel_width + (size_t)p * (size_t)panel_width) * 3,
                   (size_t)panel_width * 3);
        if (titles && titles[p])
            draw_text(&c, p ? x0 : 2 * scale, 2 * scale + line, titles[p]);
        /* x ticks: x_left at the panel's left edge to x_right at its right */
        for (int k = 0; k <= 4; k++) {
            int x = x0 + (int)lrint((double)k / 4.0 * (panel_width - 1));
            for (int d = 1; d <= 3 * scale; d++)
                put(&c, x, top + height + d, 230);
            char label[16];
            snprintf(label, sizeof label, "%g", axes->x_left + (axes->x_right - axes->x_left) * k / 4.0);
            draw_tick_label(&c, x, top + height + 4 * scale, label, 1);
        }
        draw_tick_label(&c, x0 + panel_width / 2, top + height + 4 * scale + line, axes->x_label, 1);
    }
    /* y ticks: y_top at the top to y_bottom at the bottom */
    for (int k = 0; k <= 4; k++) {
        int y = top + (int)lrint((double)k / 4.0 * (height - 1));
        for (int d = 1; d <= 3 * scale; d++)
            put(&c, left - d, y, 230);
        char label[16];
        snprintf(label, sizeof label, "%g", axes->y_top + (axes->y_bottom - axes->y_top) * k / 4.0);
        draw_tick_label(&c, left - 4 * scale, y - 3 * scale, label, 0);
    }
    draw_text(&c, scale, top - line - scale, axes->y_label);
    /* the colour scale: the tone curve from f = 0 (bottom) to 95% of white (top), with f at ticks */
    int bar_x = c.width - right + char_w, bar_w = 2 * char_w;
    for (int y = 0; y < height; y++) {
        double v = 0.95 * (double)(height - 1 - y) / (height - 1);
        float f = (float)f_of_display(v, exposure), rgb[3] = { f, f, f };
        uint8_t px[3];
        image_tonemap(1, rgb, (float)exposure, px);
        for (int x = 0; x < bar_w; x++)
            put(&c, bar_x + x, top + y, px[0]);
    }
    static const double marks[] = { 0.0, 0.25, 0.5, 0.75, 0.95 };
    for (size_t k = 0; k < sizeof marks / sizeof marks[0]; k++) {
        int y = top + (int)lrint((1.0 - marks[k] / 0.95) * (height - 1));
        char label[16];
        snprintf(label, sizeof label, "%.2g", f_of_display(marks[k], exposure));
        for (int d = 0; d < scale * 2; d++)
            put(&c, bar_x + bar_w + d, y, 230);
        draw_text(&c, bar_x + bar_w + 3 * scale, y - 3 * scale, label);
    }
    draw_text(&c, bar_x, top - line - scale, axes->value_label);
    *out_width = c.width;
    *out_height = c.height;
    return c.rgb;
}
