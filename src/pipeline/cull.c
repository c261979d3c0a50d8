#include "cull.h"

int64_t sr_cull_area2(const sr_screen_vertex *a, const sr_screen_vertex *b, const sr_screen_vertex *c)
{
    return (b->x - a->x) * (c->y - a->y) - (b->y - a->y) * (c->x - a->x);
}

bool sr_cull_keeps(int64_t area2, sr_cull cull, sr_front front)
{
    if (area2 == 0)
        return false;
    bool clockwise = area2 > 0;
    bool is_front = (front == SR_FRONT_CW) == clockwise;
    switch (cull) {
    case SR_CULL_BACK:  return is_front;
    case SR_CULL_FRONT: return !is_front;
    case SR_CULL_NONE:  return true;
    }
    return true;
}
