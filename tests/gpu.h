/* A compute shader run on a Vulkan device for the shader tests (tests/test_shaders.c): the loader is
 * opened at run time (libvulkan.so.1), so nothing is linked and a machine without Vulkan skips them. */
#ifndef HB_TEST_GPU_H
#define HB_TEST_GPU_H

#include <stddef.h>
#include <stdint.h>

typedef struct hb_gpu hb_gpu;

/* The first Vulkan device with a compute queue (its name into name), or NULL with the reason in why. */
hb_gpu *hb_gpu_open(char *name, size_t name_size, char *why, size_t why_size);

/* Runs SPIR-V code (size bytes, entry point "main") over `groups` workgroups with `buffers` storage
 * buffers of floats bound at 0, 1, ...: data[b] holds counts[b] floats, copied in before and back
 * after the run. 0 on success, else -1 with the reason in why. */
int hb_gpu_run(hb_gpu *gpu, const uint32_t *code, size_t size, int buffers, float *const *data, const size_t *counts,
               uint32_t groups, char *why, size_t why_size);

void hb_gpu_close(hb_gpu *gpu);

#endif
