/* array.h — the growable array of fixed-size elements the library's rooms
 * share (the draw call's workspace and bins, the OBJ and MTL readers).
 *
 * An sr_array starts zeroed; every call on one array passes the same element
 * size. Growth doubles from 64 elements and never overflows size_t: a request
 * that cannot be met fails as out of memory and leaves the array unchanged. */
#ifndef SOFTRAST_CORE_ARRAY_H
#define SOFTRAST_CORE_ARRAY_H

#include <stdbool.h>
#include <stddef.h>

typedef struct sr_array {
    void *data;
    size_t count, capacity; /* in elements */
} sr_array;

/* Room for `count` elements in all; false when out of memory. */
bool sr_array_reserve(sr_array *a, size_t count, size_t elem);
/* Appends n uninitialised elements and returns the first, or NULL when out
 * of memory. Callers enforce their own count limits. */
void *sr_array_grow(sr_array *a, size_t n, size_t elem);
void sr_array_free(sr_array *a);

/* Appends one uninitialised element (NULL when out of memory). Inline: the
 * binner pushes once per triangle and tile. */
static inline void *sr_array_push(sr_array *a, size_t elem)
{
    if (a->count == a->capacity && !sr_array_reserve(a, a->count + 1, elem))
        return NULL;
    return (char *)a->data + elem * a->count++;
}

#endif
