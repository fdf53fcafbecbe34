/* hb_gpu: a compute dispatch through the Vulkan loader, opened with dlopen, its entry points looked up
 * by vkGetInstanceProcAddr and vkGetDeviceProcAddr. Host-visible coherent buffers, one descriptor set,
 * one submission, waited for. Where the headers or dlopen are missing it compiles to a stub that says so. */
#include "gpu.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__has_include)
#if __has_include(<vulkan/vulkan.h>) && __has_include(<dlfcn.h>)
#define HB_GPU_VULKAN 1
#endif
#endif

#ifndef HB_GPU_VULKAN

hb_gpu *hb_gpu_open(char *name, size_t name_size, char *why, size_t why_size)
{
    (void)name, (void)name_size;
    snprintf(why, why_size, "built without the Vulkan headers (libvulkan-dev) or dlopen");
    return NULL;
}

int hb_gpu_run(hb_gpu *gpu, const uint32_t *code, size_t size, int buffers, float *const *data, const size_t *counts,
               uint32_t groups, char *why, size_t why_size)
{
    (void)gpu, (void)code, (void)size, (void)buffers, (void)data, (void)counts, (void)groups;
    snprintf(why, why_size, "no Vulkan");
    return -1;
}

void hb_gpu_close(hb_gpu *gpu) { (void)gpu; }

#else

#define VK_NO_PROTOTYPES
#include <dlfcn.h>
#include <vulkan/vulkan.h>

#define HB_GPU_MAX_BUFFERS 8

/* The entry points used, looked up once. */
#define HB_VK_INSTANCE_FUNCTIONS(X)                                                                    \
    X(vkDestroyInstance) X(vkEnumeratePhysicalDevices) X(vkGetPhysicalDeviceProperties)                \
    X(vkGetPhysicalDeviceQueueFamilyProperties) X(vkGetPhysicalDeviceMemoryProperties) X(vkCreateDevice) \
    X(vkGetDeviceProcAddr)
#define HB_VK_DEVICE_FUNCTIONS(X)                                                                      \
    X(vkDestroyDevice) X(vkGetDeviceQueue) X(vkCreateBuffer) X(vkDestroyBuffer)                         \
    X(vkGetBufferMemoryRequirements) X(vkAllocateMemory) X(vkFreeMemory) X(vkBindBufferMemory)          \
    X(vkMapMemory) X(vkUnmapMemory) X(vkCreateShaderModule) X(vkDestroyShaderModule)                    \
    X(vkCreateDescriptorSetLayout) X(vkDestroyDescriptorSetLayout) X(vkCreatePipelineLayout)            \
    X(vkDestroyPipelineLayout) X(vkCreateComputePipelines) X(vkDestroyPipeline)                         \
    X(vkCreateDescriptorPool) X(vkDestroyDescriptorPool) X(vkAllocateDescriptorSets)                    \
    X(vkUpdateDescriptorSets) X(vkCreateCommandPool) X(vkDestroyCommandPool)                            \
    X(vkAllocateCommandBuffers) X(vkBeginCommandBuffer) X(vkEndCommandBuffer) X(vkCmdBindPipeline)      \
    X(vkCmdBindDescriptorSets) X(vkCmdDispatch) X(vkQueueSubmit) X(vkQueueWaitIdle)

#define HB_VK_MEMBER(name) PFN_##name name;

struct hb_gpu {
    void *library;
    VkInstance instance;
    VkPhysicalDevice physical;
    VkDevice device;
    VkQueue queue;
    uint32_t family;
    PFN_vkGetInstanceProcAddr vkGetInstanceProcAddr;
    HB_VK_INSTANCE_FUNCTIONS(HB_VK_MEMBER)
    HB_VK_DEVICE_FUNCTIONS(HB_VK_MEMBER)
};

static int fail(char *why, size_t size, const char *what, VkResult r)
{
    snprintf(why, size, "%s failed (VkResult %d)", what, (int)r);
    return -1;
}

static int find_device(hb_gpu *g, char *name, size_t name_size, char *why, size_t why_size)
{
    VkPhysicalDevice devices[16];
    uint32_t count = 16;
    VkResult r = g->vkEnumeratePhysicalDevices(g->instance, &count, devices);
    if ((r != VK_SUCCESS && r != VK_INCOMPLETE) || count == 0) {
        snprintf(why, why_size, "no Vulkan device (install mesa-vulkan-drivers for lavapipe)");
        return -1;
    }
    for (uint32_t d = 0; d < count; d++) {
        VkQueueFamilyProperties families[16];
        uint32_t n = 16;
        g->vkGetPhysicalDeviceQueueFamilyProperties(devices[d], &n, families);
        for (uint32_t q = 0; q < n; q++)
            if (families[q].queueFlags & VK_QUEUE_COMPUTE_BIT) {
                VkPhysicalDeviceProperties properties;
                g->vkGetPhysicalDeviceProperties(devices[d], &properties);
                snprintf(name, name_size, "%s", properties.deviceName);
                g->physical = devices[d], g->family = q;
                return 0;
            }
    }
    snprintf(why, why_size, "no Vulkan device with a compute queue");
    return -1;
}

hb_gpu *hb_gpu_open(char *name, size_t name_size, char *why, size_t why_size)
{
    hb_gpu *g = calloc(1, sizeof *g);
    if (!g)
        return NULL;
    g->library = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!g->library) {
        snprintf(why, why_size, "no Vulkan loader (libvulkan.so.1; install libvulkan1)");
        free(g);
        return NULL;
    }
    *(void **)&g->vkGetInstanceProcAddr = dlsym(g->library, "vkGetInstanceProcAddr");
    PFN_vkCreateInstance create =
        g->vkGetInstanceProcAddr ? (PFN_vkCreateInstance)g->vkGetInstanceProcAddr(NULL, "vkCreateInstance") : NULL;
    VkApplicationInfo app = { .sType = VK_STRUCTURE_TYPE_APPLICATION_INFO, .pApplicationName = "hairbsdf_tests",
                              .apiVersion = VK_API_VERSION_1_0 };
    VkInstanceCreateInfo info = { .sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, .pApplicationInfo = &app };
    VkResult r = create ? create(&info, NULL, &g->instance) : VK_ERROR_INITIALIZATION_FAILED;
    if (r != VK_SUCCESS) {
        fail(why, why_size, "vkCreateInstance", r);
        dlclose(g->library);
        free(g);
        return NULL;
    }
#define HB_VK_INSTANCE_LOAD(fn) g->fn = (PFN_##fn)g->vkGetInstanceProcAddr(g->instance, #fn);
    HB_VK_INSTANCE_FUNCTIONS(HB_VK_INSTANCE_LOAD)
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue = { .sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, .queueCount = 1,
                                      .pQueuePriorities = &priority };
    VkDeviceCreateInfo device = { .sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, .queueCreateInfoCount = 1,
                                  .pQueueCreateInfos = &queue };
    if (find_device(g, name, name_size, why, why_size) != 0 ||
        (queue.queueFamilyIndex = g->family,
         (r = g->vkCreateDevice(g->physical, &device, NULL, &g->device)) != VK_SUCCESS &&
             fail(why, why_size, "vkCreateDevice", r))) {
        g->vkDestroyInstance(g->instance, NULL);
        dlclose(g->library);
        free(g);
        return NULL;
    }
#define HB_VK_DEVICE_LOAD(fn) g->fn = (PFN_##fn)g->vkGetDeviceProcAddr(g->device, #fn);
    HB_VK_DEVICE_FUNCTIONS(HB_VK_DEVICE_LOAD)
    g->vkGetDeviceQueue(g->device, g->family, 0, &g->queue);
    return g;
}

/* A host-visible, coherent storage buffer of `bytes`. */
static int make_buffer(hb_gpu *g, VkDeviceSize bytes, VkBuffer *buffer, VkDeviceMemory *memory, char *why,
                       size_t why_size)
{
    VkBufferCreateInfo info = { .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = bytes,
                                .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                .sharingMode = VK_SHARING_MODE_EXCLUSIVE };
    VkResult r = g->vkCreateBuffer(g->device, &info, NULL, buffer);
    if (r != VK_SUCCESS)
        return fail(why, why_size, "vkCreateBuffer", r);
    VkMemoryRequirements need;
    g->vkGetBufferMemoryRequirements(g->device, *buffer, &need);
    VkPhysicalDeviceMemoryProperties memory_types;
    g->vkGetPhysicalDeviceMemoryProperties(g->physical, &memory_types);
    const VkMemoryPropertyFlags wanted = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    uint32_t type = memory_types.memoryTypeCount;
    for (uint32_t k = 0; k < memory_types.memoryTypeCount && type == memory_types.memoryTypeCount; k++)
        if ((need.memoryTypeBits >> k & 1u) && (memory_types.memoryTypes[k].propertyFlags & wanted) == wanted)
            type = k;
    if (type == memory_types.memoryTypeCount) {
        snprintf(why, why_size, "no host-visible coherent memory");
        return -1;
    }
    VkMemoryAllocateInfo allocate = { .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = need.size,
                                      .memoryTypeIndex = type };
    if ((r = g->vkAllocateMemory(g->device, &allocate, NULL, memory)) != VK_SUCCESS)
        return fail(why, why_size, "vkAllocateMemory", r);
    if ((r = g->vkBindBufferMemory(g->device, *buffer, *memory, 0)) != VK_SUCCESS)
        return fail(why, why_size, "vkBindBufferMemory", r);
    return 0;
}

static int copy(hb_gpu *g, VkDeviceMemory memory, float *data, size_t bytes, int to_device)
{
    void *mapped;
    if (g->vkMapMemory(g->device, memory, 0, bytes, 0, &mapped) != VK_SUCCESS)
        return -1;
    if (to_device)
        memcpy(mapped, data, bytes);
    else
        memcpy(data, mapped, bytes);
    g->vkUnmapMemory(g->device, memory);
    return 0;
}

/* Everything one run creates, released together. */
typedef struct run_objects {
    VkBuffer buffer[HB_GPU_MAX_BUFFERS];
    VkDeviceMemory memory[HB_GPU_MAX_BUFFERS];
    VkShaderModule module;
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    VkDescriptorPool pool;
    VkCommandPool commands;
} run_objects;

static void release(hb_gpu *g, run_objects *o)
{
    g->vkQueueWaitIdle(g->queue);
    g->vkDestroyCommandPool(g->device, o->commands, NULL);
    g->vkDestroyDescriptorPool(g->device, o->pool, NULL);
    g->vkDestroyPipeline(g->device, o->pipeline, NULL);
    g->vkDestroyPipelineLayout(g->device, o->layout, NULL);
    g->vkDestroyDescriptorSetLayout(g->device, o->set_layout, NULL);
    g->vkDestroyShaderModule(g->device, o->module, NULL);
    for (int b = 0; b < HB_GPU_MAX_BUFFERS; b++) {
        g->vkDestroyBuffer(g->device, o->buffer[b], NULL);
        g->vkFreeMemory(g->device, o->memory[b], NULL);
    }
}

/* The pipeline of one compute shader whose buffers are storage buffers 0 .. buffers - 1. */
static int make_pipeline(hb_gpu *g, run_objects *o, const uint32_t *code, size_t size, int buffers, char *why,
                         size_t why_size)
{
    VkShaderModuleCreateInfo module = { .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, .codeSize = size,
                                        .pCode = code };
    VkResult r = g->vkCreateShaderModule(g->device, &module, NULL, &o->module);
    if (r != VK_SUCCESS)
        return fail(why, why_size, "vkCreateShaderModule", r);
    VkDescriptorSetLayoutBinding bindings[HB_GPU_MAX_BUFFERS];
    for (int b = 0; b < buffers; b++)
        bindings[b] = (VkDescriptorSetLayoutBinding){ .binding = (uint32_t)b,
                                                      .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                                      .descriptorCount = 1, .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT };
    VkDescriptorSetLayoutCreateInfo set = { .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                            .bindingCount = (uint32_t)buffers, .pBindings = bindings };
    if ((r = g->vkCreateDescriptorSetLayout(g->device, &set, NULL, &o->set_layout)) != VK_SUCCESS)
        return fail(why, why_size, "vkCreateDescriptorSetLayout", r);
    VkPipelineLayoutCreateInfo layout = { .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, .setLayoutCount = 1,
                                          .pSetLayouts = &o->set_layout };
    if ((r = g->vkCreatePipelineLayout(g->device, &layout, NULL, &o->layout)) != VK_SUCCESS)
        return fail(why, why_size, "vkCreatePipelineLayout", r);
    VkComputePipelineCreateInfo pipeline = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = { .sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                   .module = o->module, .pName = "main" },
        .layout = o->layout };
    if ((r = g->vkCreateComputePipelines(g->device, VK_NULL_HANDLE, 1, &pipeline, NULL, &o->pipeline)) != VK_SUCCESS)
        return fail(why, why_size, "vkCreateComputePipelines", r);
    return 0;
}

/* One descriptor set over the run's buffers, a command buffer that dispatches, its submission. */
static int dispatch(hb_gpu *g, run_objects *o, int buffers, const size_t *counts, uint32_t groups, char *why,
                    size_t why_size)
{
    VkDescriptorPoolSize pool_size = { VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, (uint32_t)buffers };
    VkDescriptorPoolCreateInfo pool = { .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, .maxSets = 1,
                                        .poolSizeCount = 1, .pPoolSizes = &pool_size };
    VkResult r = g->vkCreateDescriptorPool(g->device, &pool, NULL, &o->pool);
    if (r != VK_SUCCESS)
        return fail(why, why_size, "vkCreateDescriptorPool", r);
    VkDescriptorSet set;
    VkDescriptorSetAllocateInfo allocate = { .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                             .descriptorPool = o->pool, .descriptorSetCount = 1,
                                             .pSetLayouts = &o->set_layout };
    if ((r = g->vkAllocateDescriptorSets(g->device, &allocate, &set)) != VK_SUCCESS)
        return fail(why, why_size, "vkAllocateDescriptorSets", r);
    VkDescriptorBufferInfo infos[HB_GPU_MAX_BUFFERS];
    VkWriteDescriptorSet writes[HB_GPU_MAX_BUFFERS];
    for (int b = 0; b < buffers; b++) {
        infos[b] = (VkDescriptorBufferInfo){ o->buffer[b], 0, counts[b] * sizeof(float) };
        writes[b] = (VkWriteDescriptorSet){ .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = set,
                                            .dstBinding = (uint32_t)b, .descriptorCount = 1,
                                            .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                            .pBufferInfo = &infos[b] };
    }
    g->vkUpdateDescriptorSets(g->device, (uint32_t)buffers, writes, 0, NULL);
    VkCommandPoolCreateInfo commands = { .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                         .queueFamilyIndex = g->family };
    if ((r = g->vkCreateCommandPool(g->device, &commands, NULL, &o->commands)) != VK_SUCCESS)
        return fail(why, why_size, "vkCreateCommandPool", r);
    VkCommandBuffer cb;
    VkCommandBufferAllocateInfo cb_info = { .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                            .commandPool = o->commands, .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                            .commandBufferCount = 1 };
    if ((r = g->vkAllocateCommandBuffers(g->device, &cb_info, &cb)) != VK_SUCCESS)
        return fail(why, why_size, "vkAllocateCommandBuffers", r);
    VkCommandBufferBeginInfo begin = { .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                       .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT };
    g->vkBeginCommandBuffer(cb, &begin);
    g->vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, o->pipeline);
    g->vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, o->layout, 0, 1, &set, 0, NULL);
    g->vkCmdDispatch(cb, groups, 1, 1);
    if ((r = g->vkEndCommandBuffer(cb)) != VK_SUCCESS)
        return fail(why, why_size, "vkEndCommandBuffer", r);
    VkSubmitInfo submit = { .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &cb };
    if ((r = g->vkQueueSubmit(g->queue, 1, &submit, VK_NULL_HANDLE)) != VK_SUCCESS)
        return fail(why, why_size, "vkQueueSubmit", r);
    if ((r = g->vkQueueWaitIdle(g->queue)) != VK_SUCCESS)
        return fail(why, why_size, "vkQueueWaitIdle", r);
    return 0;
}

int hb_gpu_run(hb_gpu *g, const uint32_t *code, size_t size, int buffers, float *const *data, const size_t *counts,
               uint32_t groups, char *why, size_t why_size)
{
    if (buffers < 1 || buffers > HB_GPU_MAX_BUFFERS) {
        snprintf(why, why_size, "%d buffers (1 to %d)", buffers, HB_GPU_MAX_BUFFERS);
        return -1;
    }
    run_objects o;
    memset(&o, 0, sizeof o);
    int st = make_pipeline(g, &o, code, size, buffers, why, why_size);
    for (int b = 0; st == 0 && b < buffers; b++)
        st = make_buffer(g, counts[b] * sizeof(float), &o.buffer[b], &o.memory[b], why, why_size) ||
                     copy(g, o.memory[b], data[b], counts[b] * sizeof(float), 1)
                 ? -1 : 0;
    if (st == 0)
        st = dispatch(g, &o, buffers, counts, groups, why, why_size);
    for (int b = 0; st == 0 && b < buffers; b++)
        st = copy(g, o.memory[b], data[b], counts[b] * sizeof(float), 0);
    release(g, &o);
    return st;
}

void hb_gpu_close(hb_gpu *g)
{
    if (!g)
        return;
    g->vkDestroyDevice(g->device, NULL);
    g->vkDestroyInstance(g->instance, NULL);
    dlclose(g->library);
    free(g);
}

#endif
