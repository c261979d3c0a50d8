#include <math.h>
#include <stdlib.h>

#include "mesh_bounds.h"
#include "pipeline/02_assemble.h"
#include "softrast/softrast.h"
#include "core/error.h"

static void *alloc_array(bool wanted, uint32_t count, size_t elem, bool *ok)
{
    if (!wanted || count == 0)
        return NULL;
    void *p = calloc(count, elem);
    if (!p)
        *ok = false;
    return p;
}

bool sr_mesh_alloc(sr_mesh *mesh, uint32_t vertex_count, uint32_t index_count,
                   bool normals, bool uvs, bool colors, sr_error *err)
{
    bool ok = true;
    *mesh = (sr_mesh){ .vertex_count = vertex_count, .index_count = index_count };
    mesh->positions = alloc_array(true, vertex_count, sizeof(vec3), &ok);
    mesh->normals = alloc_array(normals, vertex_count, sizeof(vec3), &ok);
    mesh->uvs = alloc_array(uvs, vertex_count, sizeof(vec2), &ok);
    mesh->colors = alloc_array(colors, vertex_count, sizeof(vec3), &ok);
    mesh->indices = alloc_array(true, index_count, sizeof(uint32_t), &ok);
    if (!ok) {
        sr_mesh_free(mesh);
        return sr_error_set(err, "out of memory for a mesh of %u vertices and %u indices",
                            vertex_count, index_count);
    }
    return true;
}

void sr_mesh_free(sr_mesh *mesh)
{
    free(mesh->positions);
    free(mesh->clip_positions);
    free(mesh->normals);
    free(mesh->uvs);
    free(mesh->colors);
    free(mesh->indices);
    free(mesh->texture_path);
    free(mesh->parts);
    free(mesh->file_faces);
    for (uint32_t i = 0; mesh->materials && i < mesh->material_count; i++)
        free(mesh->materials[i].texture_path);
    free(mesh->materials);
    *mesh = (sr_mesh){ 0 };
}

/* The bounds of the positions, a non-finite one skipped (skip) or ending
 * the walk with false; false too when none is finite. */
static bool bounds_of(const sr_mesh *mesh, vec3 lo, vec3 hi, bool skip)
{
    bool any = false;
    for (uint32_t i = 0; mesh->positions && i < mesh->vertex_count; i++) {
        const float *p = mesh->positions[i];
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) {
            if (!skip)
                return false;
            continue;
        }
        if (!any) {
            glm_vec3_copy((float *)p, lo);
            glm_vec3_copy((float *)p, hi);
            any = true;
        }
        glm_vec3_minv(lo, (float *)p, lo);
        glm_vec3_maxv(hi, (float *)p, hi);
    }
    return any;
}

bool sr_mesh_bounds(const sr_mesh *mesh, vec3 lo, vec3 hi)
{
    return bounds_of(mesh, lo, hi, false);
}

bool sr_mesh_finite_bounds(const sr_mesh *mesh, vec3 lo, vec3 hi)
{
    return bounds_of(mesh, lo, hi, true);
}

uint32_t sr_mesh_triangle_slots(const sr_mesh *mesh)
{
    return sr_assemble_slots(mesh);
}

/* A power of two that brings the mesh's largest coordinate near 1: edges
 * scaled by it keep their area weights' ratios exactly, and their cross
 * products neither overflow (edges past about 1e19 would) nor underflow. */
static float normal_scale(const sr_mesh *mesh)
{
    vec3 lo, hi;
    if (!sr_mesh_finite_bounds(mesh, lo, hi)) /* a vertex at NaN leaves the others their scale */
        return 1.0f;
    float largest = 0.0f;
    for (int k = 0; k < 3; k++)
        largest = fmaxf(largest, fmaxf(fabsf(lo[k]), fabsf(hi[k])));
    int exponent = 0;
    frexpf(largest, &exponent);
    return largest > 0.0f && isfinite(largest) ? ldexpf(1.0f, -exponent) : 1.0f;
}

bool sr_mesh_compute_normals(sr_mesh *mesh, sr_error *err)
{
    if (mesh->normals || mesh->vertex_count == 0)
        return true;
    if (!mesh->positions)
        return sr_error_set(err, "smooth normals need the mesh's positions");
    if (!sr_assemble_indices_valid(mesh))
        return sr_error_set(err, "mesh has an index past its %u vertices", mesh->vertex_count);
    mesh->normals = calloc(mesh->vertex_count, sizeof(vec3));
    if (!mesh->normals)
        return sr_error_set(err, "out of memory for %u normals", mesh->vertex_count);
    uint32_t slots = sr_mesh_triangle_slots(mesh);
    float scale = normal_scale(mesh);
    for (uint32_t k = 0; k < slots; k++) {
        uint32_t t[3];
        if (!sr_assemble_triangle(mesh, k, t))
            continue;
        vec3 e1, e2, n;
        glm_vec3_sub(mesh->positions[t[1]], mesh->positions[t[0]], e1);
        glm_vec3_sub(mesh->positions[t[2]], mesh->positions[t[0]], e2);
        glm_vec3_scale(e1, scale, e1);
        glm_vec3_scale(e2, scale, e2);
        /* Left-handed, clockwise front faces: e1 x e2 points outward. */
        glm_vec3_cross(e1, e2, n);
        for (int i = 0; i < 3; i++)
            glm_vec3_add(mesh->normals[t[i]], n, mesh->normals[t[i]]);
    }
    for (uint32_t i = 0; i < mesh->vertex_count; i++)
        glm_vec3_normalize(mesh->normals[i]);
    return true;
}

void sr_mesh_update_bounds(sr_mesh *mesh)
{
    mesh->bounded = sr_mesh_bounds(mesh, mesh->bounds_lo, mesh->bounds_hi);
}

bool sr_mesh_set_origin(sr_mesh *mesh, const double origin[3], sr_error *err)
{
    for (int k = 0; k < 3; k++)
        if (!isfinite(origin[k]))
            return sr_error_set(err, "mesh origin (%g, %g, %g) is not finite", origin[0], origin[1], origin[2]);
    for (int k = 0; k < 3; k++)
        mesh->origin[k] = origin[k];
    return true;
}
