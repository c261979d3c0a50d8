/* amf_two_volumes.h — an AMF object of two volumes over five vertices, for
 * tests of the volumes Assimp 5.2 drops (src/io/amf_volumes.h): volume
 * one, material 2, a tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1); volume
 * two, material 3, a three-sided pyramid below it down to (0,0,−2), the
 * one vertex only it uses listed in the middle. */
#ifndef SOFTRAST_TESTS_AMF_TWO_VOLUMES_H
#define SOFTRAST_TESTS_AMF_TWO_VOLUMES_H

#define AMF_VERTEX(x, y, z) "<vertex><coordinates><x>" #x "</x><y>" #y "</y><z>" #z "</z></coordinates></vertex>"
#define AMF_TRIANGLE(a, b, c) "<triangle><v1>" #a "</v1><v2>" #b "</v2><v3>" #c "</v3></triangle>"

#define AMF_TWO_VOLUMES(id)                                                                                   \
    "<object id=\"" id "\"><metadata type=\"name\">two</metadata><mesh><vertices>" AMF_VERTEX(0, 0, 0)       \
        AMF_VERTEX(1, 0, 0) AMF_VERTEX(0, 0, -2) AMF_VERTEX(0, 1, 0) AMF_VERTEX(0, 0, 1)                      \
        "</vertices>\n<volume materialid=\"2\">" AMF_TRIANGLE(0, 3, 1) AMF_TRIANGLE(0, 1, 4)                  \
            AMF_TRIANGLE(0, 4, 3) AMF_TRIANGLE(1, 3, 4) "</volume>\n<volume materialid=\"3\">"                \
                AMF_TRIANGLE(0, 1, 2) AMF_TRIANGLE(1, 3, 2) AMF_TRIANGLE(3, 0, 2) "</volume></mesh></object>\n"

#endif
