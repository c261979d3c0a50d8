#include <math.h>

#include "flycam.h"

sr_flycam sr_flycam_from_camera(const sr_camera *cam)
{
    vec3 d;
    glm_vec3_sub((float *)cam->target, (float *)cam->eye, d);
    float horizontal = sqrtf(d[0] * d[0] + d[2] * d[2]);
    sr_flycam fly = { .yaw = glm_deg(atan2f(d[0], d[2])), .pitch = glm_deg(atan2f(d[1], horizontal)) };
    glm_vec3_copy((float *)cam->eye, fly.position);
    sr_flycam_turn(&fly, 0.0f, 0.0f);
    return fly;
}

void sr_flycam_basis(const sr_flycam *fly, vec3 forward, vec3 right, vec3 up)
{
    float yaw = glm_rad(fly->yaw), pitch = glm_rad(fly->pitch);
    glm_vec3_copy((vec3){ sinf(yaw) * cosf(pitch), sinf(pitch), cosf(yaw) * cosf(pitch) }, forward);
    glm_vec3_copy((vec3){ cosf(yaw), 0.0f, -sinf(yaw) }, right);
    /* Left-handed: up = forward × right. */
    glm_vec3_cross(forward, right, up);
}

void sr_flycam_move(sr_flycam *fly, float forward, float right, float up)
{
    vec3 f, r, u;
    sr_flycam_basis(fly, f, r, u);
    glm_vec3_muladds(f, forward, fly->position);
    glm_vec3_muladds(r, right, fly->position);
    fly->position[1] += up;
}

void sr_flycam_turn(sr_flycam *fly, float yaw_deg, float pitch_deg)
{
    fly->yaw = fmodf(fly->yaw + yaw_deg, 360.0f);
    fly->pitch = glm_clamp(fly->pitch + pitch_deg, -SR_FLYCAM_MAX_PITCH, SR_FLYCAM_MAX_PITCH);
}

void sr_flycam_apply(const sr_flycam *fly, sr_camera *cam)
{
    vec3 f, r, u;
    sr_flycam_basis(fly, f, r, u);
    glm_vec3_copy((float *)fly->position, cam->eye);
    glm_vec3_add((float *)fly->position, f, cam->target);
    glm_vec3_copy(u, cam->up);
}
