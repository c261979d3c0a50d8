/* An AMF file, which softrast reads itself before Assimp does
 * (src/io/amf_import.h), refused in one line when it is bad: no crash, no
 * hang, no huge allocation. Its constellations read right are
 * tests/test_instances.c's. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "cli_error.h"
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

/* The library's refusal of a large file, which the program would precede
 * with its line saying that a slow load is under way: one line naming the
 * file, the mesh left empty. */
static void assert_load_refused(const char *name, const char *needle)
{
    char path[600];
    temp_path(path, sizeof path, name);
    sr_mesh m;
    sr_texture tex = { 0 };
    sr_error err = { "" };
    cr_assert_not(sr_mesh_load(&m, &tex, path, &err), "%s loaded", name);
    cr_assert_eq(strncmp(err.message, path, strlen(path)), 0, "not naming the file: %s", err.message);
    cr_assert_null(strchr(err.message, '\n'), "more than one line: %s", err.message);
    cr_assert_not_null(strstr(err.message, needle), "'%s' not in: %s", needle, err.message);
    cr_assert(m.positions == NULL && m.vertex_count == 0 && tex.texels == NULL);
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
