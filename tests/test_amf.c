/* An AMF file, which softrast reads itself before Assimp does
 * (src/io/amf_import.h): its unit read wherever its root stands, and the
 * file refused in one line when it is bad: no crash, no hang, no huge
 * allocation. Its volumes and constellations read right are
 * tests/test_instances.c's. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "amf_two_volumes.h"
#include "cli_error.h"
#include "load_refused.h"
#include "run_helpers.h"
#include "softrast/files.h"
#include "temp_dir.h"

TestSuite(amf, .init = temp_dir_make, .fini = temp_dir_remove);

static void write_bytes(const char *name, const char *bytes, size_t len)
{
    char path[600];
    FILE *f = fopen(temp_path(path, sizeof path, name), "wb");
    cr_assert_not_null(f);
    cr_assert_eq(fwrite(bytes, 1, len, f), len);
    fclose(f);
}

/* The root's unit is an attribute like any other, however long the
 * comment before it (the head of the file alone was read for it). */
Test(amf, the_unit_is_read_after_a_long_prologue)
{
    char text[8192] = "<?xml version=\"1.0\"?>\n<!-- ";
    for (int i = 0; i < 4000; i++)
        strcat(text, "c");
    strcat(text, " -->\n<amf version=\"1.1\"\n     unit=\"inch\"><object id=\"1\"><mesh><vertices>" AMF_VERTEX(0, 0, 0)
                     AMF_VERTEX(1, 0, 0) AMF_VERTEX(0, 1, 0) "</vertices><volume>" AMF_TRIANGLE(0, 1, 2)
                         "</volume></mesh></object></amf>\n");
    write_text(temp_dir, "unit.amf", text);
    char args[700];
    snprintf(args, sizeof args, "info %s/unit.amf", temp_dir);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_assert_not_null(strstr(r.out, "units: 0.0254 m per unit (read: "), "%s", r.out);
}

Test(amf, a_zipped_amf_is_refused_as_such)
{
    static const char ZIP[] = "PK\3\4\24\0\0\0\10\0garbage after a zip header";
    write_bytes("zipped.amf", ZIP, sizeof ZIP - 1);
    assert_one_error("info %s/zipped.amf", "a zipped AMF");
}

Test(amf, malformed_xml_names_its_line)
{
    write_text(temp_dir, "bad.amf", "<?xml version=\"1.0\"?>\n<amf>\n<object id=\"1\">\n</amf>\n");
    assert_one_error("info %s/bad.amf", "bad.amf:4: not well-formed AMF XML (mismatched tag)");
}

Test(amf, a_declared_entity_is_refused)
{
    write_text(temp_dir, "entity.amf",
               "<?xml version=\"1.0\"?>\n<!DOCTYPE amf [<!ENTITY a \"aaaaaaaaaa\"><!ENTITY b \"&a;&a;&a;&a;\">]>\n"
               "<amf><metadata type=\"name\">&b;&b;&b;</metadata></amf>\n");
    assert_one_error("info %s/entity.amf", "declares an entity");
}

Test(amf, a_corner_past_the_vertices_of_a_split_object_is_refused)
{
    char text[4096];
    snprintf(text, sizeof text, "<amf>%s</amf>", AMF_TWO_VOLUMES("1"));
    char *corner = strstr(text, "<v3>2</v3>");
    cr_assert_not_null(corner);
    memcpy(corner, "<v3>9</v3>", 10);
    write_text(temp_dir, "corner.amf", text);
    assert_one_error("info %s/corner.amf", "has a triangle corner \"9\", not one of its 5 vertices");
}

Test(amf, an_id_with_a_hash_in_a_file_to_split_is_refused)
{
    write_text(temp_dir, "hash.amf", "<amf>" AMF_TWO_VOLUMES("a#1") "</amf>");
    assert_one_error("info %s/hash.amf", "holds '#'");
}

/* 2^20 + 1 constellations, 17 MB of them: past the reader's cap. */
Test(amf, more_constellations_than_the_cap_are_refused)
{
    char path[600];
    FILE *f = fopen(temp_path(path, sizeof path, "many.amf"), "wb");
    cr_assert_not_null(f);
    fputs("<amf>", f);
    for (unsigned i = 0; i <= 1u << 20; i++)
        fputs("<constellation/>", f);
    fputs("</amf>", f);
    fclose(f);
    assert_load_refused("many.amf", "more than 1048576 AMF constellations");
}

/* An object whose one metadata of 1 MiB would be copied into each of its
 * 100 volumes' objects: past 8 times the file's size and 16 MiB. */
Test(amf, a_split_past_its_cap_is_refused)
{
    char path[600];
    FILE *f = fopen(temp_path(path, sizeof path, "wide.amf"), "wb");
    cr_assert_not_null(f);
    fputs("<amf><object id=\"1\"><metadata type=\"name\">", f);
    for (int i = 0; i < 1 << 20; i++)
        fputc('m', f);
    fputs("</metadata><mesh><vertices>" AMF_VERTEX(0, 0, 0) AMF_VERTEX(1, 0, 0) AMF_VERTEX(0, 1, 0) "</vertices>", f);
    for (int i = 0; i < 100; i++)
        fputs("<volume>" AMF_TRIANGLE(0, 1, 2) "</volume>", f);
    fputs("</mesh></object></amf>", f);
    fclose(f);
    assert_load_refused("wide.amf", "splitting its AMF objects' volumes apart would take more than");
}
