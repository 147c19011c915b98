/* test_enum.c: the name tables of enumerations (vx_enum.h): lookups both
 * ways, aliases, case folding, byte spans, the list of names for messages,
 * and every table the library exports. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "vx_cell.h"
#include "vx_compare.h"
#include "vx_enum.h"
#include "vx_grid.h"
#include "vx_import.h"
#include "vx_irrvol.h"
#include "vx_plan.h"
#include "vx_scene.h"
#include "vx_tonemap.h"

enum { C_UNKNOWN = 0, C_RED, C_GREEN, C_BLUE };

static const vx_enum_name color_names[] = {
	{ "red", C_RED }, { "green", C_GREEN }, { "verde", C_GREEN },
	{ "blue", C_BLUE }, { NULL, C_UNKNOWN }
};
static const vx_enum colors = { "color", color_names, "unknown", 0 };
static const vx_enum colors_fold = { "color", color_names, "?", 1 };

/* Each lookup against the table above (the oracle: the table itself). */
static void
lookups(void **state)
{
	static const struct {
		const char *s;
		int value, folded;    /* vx_enum_val without and with folding */
	} t[] = {
		{ "red", C_RED, C_RED },
		{ "green", C_GREEN, C_GREEN },
		{ "verde", C_GREEN, C_GREEN },        /* an alias */
		{ "blue", C_BLUE, C_BLUE },
		{ "Red", C_UNKNOWN, C_RED },          /* case */
		{ "VERDE", C_UNKNOWN, C_GREEN },
		{ "re", C_UNKNOWN, C_UNKNOWN },       /* a prefix */
		{ "redd", C_UNKNOWN, C_UNKNOWN },     /* longer */
		{ "", C_UNKNOWN, C_UNKNOWN },
		{ "red ", C_UNKNOWN, C_UNKNOWN },
		{ "unknown", C_UNKNOWN, C_UNKNOWN },  /* the unknown name */
	};
	size_t i;

	(void)state;
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		if (vx_enum_val(&colors, t[i].s) != t[i].value ||
		    vx_enum_val(&colors_fold, t[i].s) != t[i].folded)
			fail_msg("'%s': %d %d, want %d %d", t[i].s,
			    vx_enum_val(&colors, t[i].s),
			    vx_enum_val(&colors_fold, t[i].s), t[i].value,
			    t[i].folded);
	}
	/* names: the first entry of a value, never an alias */
	assert_string_equal(vx_enum_str(&colors, C_GREEN), "green");
	assert_string_equal(vx_enum_str(&colors, C_BLUE), "blue");
	assert_string_equal(vx_enum_str(&colors, C_UNKNOWN), "unknown");
	assert_string_equal(vx_enum_str(&colors, 99), "unknown");
	assert_string_equal(vx_enum_str(&colors_fold, -1), "?");
}

/* Spans: the n bytes only, not NUL-terminated; a NUL inside matches
 * nothing (a name never holds one). */
static void
spans(void **state)
{
	static const char buf[] = "greenish";
	static const char nul[] = { 'r', 'e', 'd', '\0', 'x' };

	(void)state;
	assert_int_equal(vx_enum_val_n(&colors, buf, 5), C_GREEN);
	assert_int_equal(vx_enum_val_n(&colors, buf, 4), C_UNKNOWN);
	assert_int_equal(vx_enum_val_n(&colors, buf, 6), C_UNKNOWN);
	assert_int_equal(vx_enum_val_n(&colors, buf, 0), C_UNKNOWN);
	assert_int_equal(vx_enum_val_n(&colors, nul, 3), C_RED);
	assert_int_equal(vx_enum_val_n(&colors, nul, 4), C_UNKNOWN);
	assert_int_equal(vx_enum_val_n(&colors, nul, 5), C_UNKNOWN);
	assert_int_equal(vx_enum_val_n(&colors_fold, "BLUE", 4), C_BLUE);
}

/* The list for messages: names in table order, aliases left out, "..."
 * where the buffer ends (never past it). */
static void
list(void **state)
{
	static const struct {
		size_t size;
		const char *want;
	} t[] = {
		{ 64, "red, green, blue" },
		{ 17, "red, green, blue" },   /* exactly fits */
		{ 16, "red, green, ..." },
		{ 12, "red, ..." },
		{ 9, "red, ..." },
		{ 8, "..." },                 /* "red, ..." would not fit */
		{ 4, "..." },
	};
	char buf[80];
	size_t i;

	(void)state;
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		memset(buf, 'x', sizeof buf);
		vx_enum_list(&colors, buf, t[i].size);
		if (strcmp(buf, t[i].want) != 0)
			fail_msg("size %zu: '%s', want '%s'", t[i].size, buf,
			    t[i].want);
		assert_true(strlen(buf) < t[i].size);
		assert_int_equal(buf[t[i].size], 'x');
	}
}

static void
parse(void **state)
{
	vx_err e = { 0, "" };
	int v = -7;

	(void)state;
	assert_int_equal(vx_enum_parse(&colors, "verde", &v, 64, &e), 0);
	assert_int_equal(v, C_GREEN);
	assert_int_equal(e.code, 0);
	assert_int_equal(vx_enum_parse(&colors, "mauve", &v, 65, &e), 65);
	assert_int_equal(e.code, 65);
	assert_string_equal(e.msg,
	    "unknown color 'mauve' (one of: red, green, blue)");
	assert_int_equal(v, C_GREEN);      /* left alone on failure */
}

/* Every table the library exports: each value of its range has a name
 * that reads back as that value, no name is listed twice, and the value
 * of an unknown name is not one of the range. */
static void
library_tables(void **state)
{
	static const struct {
		const vx_enum *en;
		int first, last;     /* the named values: first .. last - 1 */
	} t[] = {
		{ &vx_view_enum, VX_VIEW_FRONT, VX_VIEW_LAST },
		{ &vx_projection_enum, VX_PERSPECTIVE, VX_PROJECTION_LAST },
		{ &vx_type_enum, VX_U8, VX_TYPE_LAST },
		{ &vx_scalar_enum, VX_S_U8, VX_SCALAR_LAST },
		{ &vx_format_enum, VX_FORMAT_RAW, VX_FORMAT_LAST },
		{ &vx_synth_enum, VX_SYNTH_SPHERE, VX_SYNTH_LAST },
		{ &vx_endian_enum, 0, 2 },
		{ &vx_plan_state_enum, VX_PLAN_ON, VX_PLAN_LAST },
		{ &vx_light_type_enum, VX_LIGHT_POINT, VX_LIGHT_LAST },
		{ &vx_falloff_enum, VX_FALLOFF_NONE, VX_FALLOFF_LAST },
		{ &vx_env_layout_enum, VX_ENV_LATLONG, VX_ENV_LAYOUT_LAST },
		{ &vx_illum_enum, VX_ILLUM_LOCAL, VX_ILLUM_LAST },
		{ &vx_interp_enum, VX_INTERP_NEAREST, VX_INTERP_LAST },
		{ &vx_phase_enum, VX_PHASE_ISOTROPIC, VX_PHASE_LAST },
		{ &vx_colormap_enum, VX_COLORMAP_GRAY, VX_COLORMAP_LAST },
		{ &vx_tonemap_op_enum, VX_TM_CLAMP, VX_TM_LAST },
		{ &vx_diff_map_enum, VX_DIFF_ABS, VX_DIFF_LAST },
		{ &vx_cell_solver_enum, VX_CELL_EXACT, VX_CELL_SOLVER_LAST },
		{ &vx_irr_store_enum, VX_IRR_ACCUM, VX_IRR_STORE_LAST },
	};
	size_t i;
	int v;

	(void)state;
	for (i = 0; i < sizeof t / sizeof t[0]; i++) {
		const vx_enum *en = t[i].en;
		const vx_enum_name *k, *j;

		for (v = t[i].first; v < t[i].last; v++) {
			const char *s = vx_enum_str(en, v);

			if (s == en->unknown || vx_enum_val(en, s) != v)
				fail_msg("%s %d: named '%s'", en->what, v, s);
		}
		for (k = en->names; k->name != NULL; k++)
			for (j = en->names; j < k; j++)
				if (strcmp(j->name, k->name) == 0)
					fail_msg("%s: '%s' twice", en->what,
					    k->name);
		assert_true(k->value < t[i].first || k->value >= t[i].last);
	}
	/* effects: one name per bit */
	for (v = 0; v < 7; v++)
		assert_int_equal(vx_enum_val(&vx_effect_enum,
		    vx_enum_str(&vx_effect_enum, 1u << v)), 1 << v);
	assert_true(VX_FX_ALL == (1u << 7) - 1);
	assert_null(vx_enum_str(&vx_effect_enum, 1u << 7));
	assert_null(vx_enum_str(&vx_effect_enum, 0));
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(lookups),
		cmocka_unit_test(spans),
		cmocka_unit_test(list),
		cmocka_unit_test(parse),
		cmocka_unit_test(library_tables),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
