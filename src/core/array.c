#include <stdint.h>
#include <stdlib.h>

#include "array.h"

bool sr_array_reserve(sr_array *a, size_t count, size_t elem)
{
    if (count <= a->capacity)
        return true;
    size_t cap = a->capacity ? a->capacity : 64;
    while (cap < count)
        cap = cap > SIZE_MAX / 2 ? count : 2 * cap;
    if (cap > SIZE_MAX / elem)
        return false;
    void *data = realloc(a->data, cap * elem);
    if (!data)
        return false;
    a->data = data;
    a->capacity = cap;
    return true;
}

void *sr_array_grow(sr_array *a, size_t n, size_t elem)
{
    if (n > SIZE_MAX - a->count || !sr_array_reserve(a, a->count + n, elem))
        return NULL;
    void *at = (char *)a->data + elem * a->count;
    a->count += n;
    return at;
}

void sr_array_free(sr_array *a)
{
    free(a->data);
    *a = (sr_array){ 0 };
}
