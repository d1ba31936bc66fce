/* What the two passes of the scene parser share (src/studies/scene.c: the first pass and the
 * driver; scene_convert.c: the second pass, typed values): the names of the sections and keys,
 * the second pass's state, the prototypes grouped by the file that defines them. */
#ifndef WHIRL_SCENE_INTERNAL_H
#define WHIRL_SCENE_INTERNAL_H

#include "whirl/common.h"
#include "whirl/scene.h"

extern const char *const sc_section_names[];

/* Every key: its section, its name and the kind of quantity its numbers are (the unit suffixes
 * they may carry). */
typedef struct sc_key_name {
    int section; /* index into sc_section_names */
    const char *name;
    whirl_quantity kind;
} sc_key_name;

/* The keys whirl_scene has no entry of line[] for (it keeps 2.3.0's size, whirl/scene.h),
 * numbered on from WHIRL_SCENE_NKEYS: [run] pivot, read into a whirl_scene_pivot. */
enum { SC_KEY_RUN_PIVOT = WHIRL_SCENE_NKEYS, SC_NKEYS };

extern const sc_key_name sc_key_names[SC_NKEYS];

/* State of the second pass: the scene it fills, the raw text and the line of every key
 * (SC_NKEYS of each), and the pivot's path (NULL: the caller keeps none, the key is refused). */
typedef struct convert {
    whirl_scene *scene;
    char *const *raw;
    const int *line;
    whirl_scene_pivot *pivot;
} convert;

/* scene.c */
char *sc_copy_string(const char *s);
char *sc_trim(char *s);

/* scene_convert.c: "FILE:LINE: [section] key" (whirl_scene_where) of any key, line as
 * whirl_scene.line's entries; into buf, returned. */
const char *sc_where(const whirl_scene *scene, int key, int line, char *buf, size_t size);

/* scene_convert.c: the sections' values converted and checked, in this order */
int sc_convert_units(const convert *v);
int sc_convert_chain(const convert *v);
int sc_convert_start(const convert *v);
int sc_convert_run(const convert *v);
int sc_convert_output(const convert *v);
/* scene_pivot.c: [run] pivot, after the run's keys */
int sc_convert_pivot(const convert *v);
/* the path as "fourier:x1c=A,y1s=B" (only the terms that are not 0; "line:0" for a pivot that
 * does not move), which whirl_pivot_parse reads back to the same path; no spaces */
void sc_write_pivot_text(FILE *fp, const whirl_pivot_path *path);
/* the header's line "# pivot = fourier:..." when pivot is given (pivot may be NULL) */
int sc_write_pivot_line(FILE *fp, const whirl_scene_pivot *pivot);

/* scene_run.c */
/* What makes a stiff scene stiff (whirl_scene_stiff), as the subject of a sentence:
 * whirl_model_stiff_cause of the scene's chain and dissipation. */
const char *sc_stiff_cause(const whirl_scene *s);

#endif
