/* PFM and a minimal PNG encoder: deflate "stored" blocks (no compression), so any browser can
 * show the lobes without a library dependency. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"

int image_write_pfm(const char *path, int width, int height, const float *rgb)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    fprintf(f, "PF\n%d %d\n-1.0\n", width, height); /* negative scale: little-endian floats */
    for (int y = height - 1; y >= 0; y--)           /* PFM stores the bottom row first */
        fwrite(rgb + (size_t)y * width * 3, sizeof(float), (size_t)width * 3, f);
    return fclose(f) == 0 ? 0 : -1;
}

uint32_t image_crc32(const uint8_t *data, size_t n, uint32_t crc)
{
    crc = ~crc;
    for (size_t i = 0; i < n; i++) {
        crc ^= data[i];
        for (int k = 0; k < 8; k++)
            crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

uint32_t image_adler32(const uint8_t *data, size_t n)
{
    uint32_t a = 1, b = 0;
    for (size_t i = 0; i < n; i++) {
        a = (a + data[i]) % 65521u;
        b = (b + a) % 65521u;
    }
    return b << 16 | a;
}

static void put_be32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24), p[1] = (uint8_t)(v >> 16), p[2] = (uint8_t)(v >> 8), p[3] = (uint8_t)v;
}

/* One chunk: length, type, data, CRC of type and data. */
static void write_chunk(FILE *f, const char *type, const uint8_t *data, size_t n)
{
    uint8_t head[8];
    put_be32(head, (uint32_t)n);
    memcpy(head + 4, type, 4);
    uint32_t crc = image_crc32((const uint8_t *)type, 4, 0);
    crc = image_crc32(data, n, crc);
    uint8_t tail[4];
    put_be32(tail, crc);
    fwrite(head, 1, 8, f);
    if (n)
        fwrite(data, 1, n, f);
    fwrite(tail, 1, 4, f);
}

int image_write_png(const char *path, int width, int height, const uint8_t *rgb8)
{
    size_t row = (size_t)width * 3 + 1, raw_size = row * (size_t)height;
    uint8_t *raw = malloc(raw_size);
    size_t blocks = (raw_size + 65534) / 65535;
    uint8_t *z = malloc(2 + raw_size + 5 * blocks + 4);
    if (!raw || !z) {
        free(raw), free(z);
        return -1;
    }
    for (int y = 0; y < height; y++) { /* filter type 0 (none) before every row */
        raw[(size_t)y * row] = 0;
        memcpy(raw + (size_t)y * row + 1, rgb8 + (size_t)y * width * 3, (size_t)width * 3);
    }
    size_t zn = 0;
    z[zn++] = 0x78, z[zn++] = 0x01; /* zlib: deflate, 32 KiB window, no dictionary */
    for (size_t off = 0; off < raw_size; off += 65535) {
        size_t len = raw_size - off < 65535 ? raw_size - off : 65535;
        z[zn++] = off + len == raw_size; /* BFINAL, BTYPE = 00 (stored) */
        z[zn++] = (uint8_t)len, z[zn++] = (uint8_t)(len >> 8);
        z[zn++] = (uint8_t)~len, z[zn++] = (uint8_t)(~len >> 8);
        memcpy(z + zn, raw + off, len);
        zn += len;
    }
    put_be32(z + zn, image_adler32(raw, raw_size));
    zn += 4;
    uint8_t ihdr[13];
    put_be32(ihdr, (uint32_t)width);
    put_be32(ihdr + 4, (uint32_t)height);
    ihdr[8] = 8, ihdr[9] = 2, ihdr[10] = ihdr[11] = ihdr[12] = 0; /* 8-bit RGB, no interlace */
    FILE *f = fopen(path, "wb");
    int ok = f != NULL;
    if (ok) {
        static const uint8_t signature[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n' };
        fwrite(signature, 1, 8, f);
        write_chunk(f, "IHDR", ihdr, sizeof ihdr);
        write_chunk(f, "IDAT", z, zn);
        write_chunk(f, "IEND", NULL, 0);
        ok = fclose(f) == 0;
    }
    free(raw), free(z);
    return ok ? 0 : -1;
}

void image_tonemap(size_t pixels, const float *rgb, float exposure, uint8_t *rgb8)
{
    for (size_t i = 0; i < pixels * 3; i++) {
        double x = exposure * (double)rgb[i];
        x = x > 0.0 ? x / (1.0 + x) : 0.0;
        double s = x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055; /* sRGB */
        rgb8[i] = (uint8_t)lrint(fmin(fmax(s, 0.0), 1.0) * 255.0);
    }
}
