/* gltf_square.h — a glTF 2.0 unit square's buffer, views and accessors
 * (positions (0,0,0) (1,0,0) (1,1,0) (0,1,0), front side +z; accessor 0
 * the positions, 1 the indices), for test scenes that place it by nodes. */
#ifndef SOFTRAST_TESTS_GLTF_SQUARE_H
#define SOFTRAST_TESTS_GLTF_SQUARE_H

#define GLTF_UNIT_SQUARE_ARRAYS                                                                                       \
    "\"buffers\":[{\"byteLength\":60,\"uri\":\"data:application/octet-stream;base64,"                               \
    "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAACAPwAAgD8AAAAAAAAAAAAAgD8AAAAAAAABAAIAAAACAAMA\"}],"                          \
    "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},{\"buffer\":0,\"byteOffset\":48,"          \
    "\"byteLength\":12}],\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","  \
    "\"min\":[0,0,0],\"max\":[1,1,1]},{\"bufferView\":1,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}]"

#endif
