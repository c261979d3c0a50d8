/* open3d_ray_mask.c — an LD_PRELOAD shim that makes Debian's Open3D 0.16
 * RaycastingScene hit anything (docs/open3d-compare.md).
 *
 * Why: Open3D's cast_rays fills an array of Embree RTCRayHit with
 * ray.mask = 0 and hands it to rtcIntersect1M, the only intersect call
 * libOpen3D imports besides rtcOccluded1M (nm -D). Embree skips a
 * geometry when (ray.mask & geometry mask) == 0, but only when it is
 * built with ray masks (EMBREE_RAY_MASK, off by default in Embree 3):
 * Debian's libembree3 is, so as packaged every ray misses (t_hit inf, ids
 * invalid). Setting each ray's mask to all ones before the real call
 * gives the behaviour of an Embree without masks; nothing else changes.
 *
 *     cc -shared -fPIC -O2 -o build/open3d_ray_mask.so tools/open3d_ray_mask.c -ldl
 *     LD_PRELOAD=build/open3d_ray_mask.so python3 ...
 *
 * Embree 3's RTCRay (rtcore_ray.h) begins org_x, org_y, org_z, tnear,
 * dir_x, dir_y, dir_z, time, tfar, then the 32-bit mask: byte offset 36,
 * the same in an RTCRayHit, whose ray comes first. The 1M calls take
 * M rays byteStride bytes apart.
 *
 * The real function: Python loads Open3D (and with it libembree3) with
 * RTLD_LOCAL, out of the global scope RTLD_NEXT searches, so it is looked
 * up in the already-loaded libembree3.so.3 when RTLD_NEXT finds nothing.
 * Open3D's threads may race to look it up; each finds the same pointer. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RAY_MASK_OFFSET 36

typedef void (*embree_1m_fn)(void *scene, void *context, void *rays, unsigned int m, size_t stride);

static void set_masks(void *rays, unsigned int m, size_t stride)
{
    for (unsigned int i = 0; i < m; i++)
        *(uint32_t *)((char *)rays + (size_t)i * stride + RAY_MASK_OFFSET) = 0xFFFFFFFFu;
}

static embree_1m_fn real(embree_1m_fn *cached, const char *name)
{
    if (*cached)
        return *cached;
    void *fn = dlsym(RTLD_NEXT, name), *embree;
    if (!fn && (embree = dlopen("libembree3.so.3", RTLD_NOW | RTLD_NOLOAD)))
        fn = dlsym(embree, name);
    if (!fn) {
        fprintf(stderr, "open3d_ray_mask: %s not found in libembree3.so.3\n", name);
        abort();
    }
    memcpy(cached, &fn, sizeof fn); /* a data pointer to a function pointer, as POSIX allows */
    return *cached;
}

void rtcIntersect1M(void *scene, void *context, void *rayhits, unsigned int m, size_t stride)
{
    static embree_1m_fn fn;
    set_masks(rayhits, m, stride);
    real(&fn, "rtcIntersect1M")(scene, context, rayhits, m, stride);
}

void rtcOccluded1M(void *scene, void *context, void *rays, unsigned int m, size_t stride)
{
    static embree_1m_fn fn;
    set_masks(rays, m, stride);
    real(&fn, "rtcOccluded1M")(scene, context, rays, m, stride);
}
