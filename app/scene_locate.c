/* scene_locate.c - where each key of a YAML document sits: field path -> line, from libyaml's event stream.
 * Paths look like "walls[1].motion[0].velocity"; a sequence entry is "particles[2]". A syntax error is recorded
 * under the path "#error" at the line where libyaml stopped; a second document in the stream (after ---) under
 * "#second_document" at its first line (libcyaml reads the first document only, so the loader refuses it). */
#include "scene.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <yaml.h>

typedef struct {
    char *path;
    int line;
    char *value; /* the text of a scalar value at this path (NULL for keys of collections) */
} loc_entry;

struct scene_locator {
    loc_entry *e;
    size_t n, cap;
    int dup_line, dup_first; /* a key given twice in one mapping: its second line and its first */
    char dup_path[512];
    char problem[256]; /* libyaml's reason for a syntax error ("" when none) */
};

static void add(scene_locator *l, const char *path, int line)
{
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 256;
        loc_entry *ne = realloc(l->e, cap * sizeof *ne);
        if (!ne)
            return;
        l->e = ne;
        l->cap = cap;
    }
    char *p = strdup(path);
    if (p)
        l->e[l->n++] = (loc_entry){p, line, NULL};
}

/* The scalar value of the entry just added (a map key's entry, or a sequence entry's). */
static void set_value(scene_locator *l, const char *path, const char *value)
{
    if (l->n && !strcmp(l->e[l->n - 1].path, path) && !l->e[l->n - 1].value)
        l->e[l->n - 1].value = strdup(value);
}

typedef struct {
    int is_map, want_key, index;
    char prefix[512];
    char key[256];
} frame;

#define MAX_DEPTH 32

/* Path of the node that starts now under frame f (and advance f past it). */
static void child_path(frame *f, char *out, size_t len)
{
    if (f->is_map) {
        snprintf(out, len, "%s%s%s", f->prefix, f->prefix[0] ? "." : "", f->key);
        f->want_key = 1;
    } else {
        snprintf(out, len, "%s[%d]", f->prefix, f->index++);
    }
}

scene_locator *scene_locate(const char *text, size_t len)
{
    scene_locator *l = calloc(1, sizeof *l);
    yaml_parser_t p;
    if (!l || !yaml_parser_initialize(&p)) {
        free(l);
        return NULL;
    }
    yaml_parser_set_input_string(&p, (const unsigned char *)text, len);
    frame st[MAX_DEPTH];
    int depth = 0, done = 0, documents = 0;
    char path[512];
    while (!done) {
        yaml_event_t ev;
        if (!yaml_parser_parse(&p, &ev)) {
            /* a reader error (bad UTF-8, a control character) has a byte offset, not a mark: count its line */
            int at = (int)p.problem_mark.line + 1;
            if (p.error == YAML_READER_ERROR) {
                at = 1;
                for (size_t k = 0; k < p.problem_offset && k < len; k++)
                    at += text[k] == '\n';
            }
            /* an error at the end of the text (a truncated file) is the last line's, not the line after it */
            int last = 1;
            for (size_t k = 0; k + 1 < len; k++)
                last += text[k] == '\n';
            add(l, "#error", at < last ? at : last);
            snprintf(l->problem, sizeof l->problem, "%s", p.problem ? p.problem : "invalid YAML");
            break;
        }
        int line = (int)ev.start_mark.line + 1;
        switch (ev.type) {
        case YAML_SCALAR_EVENT:
            if (depth > 0) {
                frame *f = &st[depth - 1];
                if (f->is_map && f->want_key) {
                    snprintf(f->key, sizeof f->key, "%s", (const char *)ev.data.scalar.value);
                    f->want_key = 0;
                    snprintf(path, sizeof path, "%s%s%s", f->prefix, f->prefix[0] ? "." : "", f->key);
                    int first = l->dup_line ? 0 : scene_line(l, path);
                    if (first > 0) { /* the same key twice in one mapping (paths carry the sequence indices) */
                        l->dup_line = line, l->dup_first = first;
                        snprintf(l->dup_path, sizeof l->dup_path, "%s", path);
                    }
                    add(l, path, line);
                } else {
                    int is_map = f->is_map;
                    child_path(f, path, sizeof path);
                    if (!is_map)
                        add(l, path, line);
                    set_value(l, path, (const char *)ev.data.scalar.value);
                }
            }
            break;
        case YAML_MAPPING_START_EVENT:
        case YAML_SEQUENCE_START_EVENT:
            path[0] = 0;
            if (depth > 0) {
                frame *f = &st[depth - 1];
                int is_map = f->is_map;
                child_path(f, path, sizeof path);
                if (!is_map)
                    add(l, path, line);
            }
            if (depth == MAX_DEPTH) { /* deeper than any scene: stop locating */
                yaml_event_delete(&ev);
                done = 1;
                continue;
            }
            st[depth] = (frame){ev.type == YAML_MAPPING_START_EVENT, 1, 0, {0}, {0}};
            snprintf(st[depth].prefix, sizeof st[depth].prefix, "%s", path);
            depth++;
            break;
        case YAML_MAPPING_END_EVENT:
        case YAML_SEQUENCE_END_EVENT:
            if (depth > 0)
                depth--;
            break;
        case YAML_ALIAS_EVENT:
            if (depth > 0)
                child_path(&st[depth - 1], path, sizeof path);
            break;
        case YAML_DOCUMENT_START_EVENT:
            if (++documents == 2) {
                add(l, "#second_document", line);
                done = 1;
            }
            break;
        case YAML_STREAM_END_EVENT:
            done = 1;
            break;
        default:
            break;
        }
        yaml_event_delete(&ev);
    }
    yaml_parser_delete(&p);
    return l;
}

void scene_locator_free(scene_locator *l)
{
    if (!l)
        return;
    for (size_t k = 0; k < l->n; k++)
        free(l->e[k].path), free(l->e[k].value);
    free(l->e);
    free(l);
}

int scene_duplicate(const scene_locator *l, const char **path, int *first)
{
    if (!l || !l->dup_line)
        return 0;
    *path = l->dup_path;
    *first = l->dup_first;
    return l->dup_line;
}

int scene_scalar(const scene_locator *l, size_t k, const char **path, const char **value, int *line)
{
    if (!l || k >= l->n)
        return 0;
    *path = l->e[k].path;
    *value = l->e[k].value;
    *line = l->e[k].line;
    return 1;
}

int scene_line(const scene_locator *l, const char *path)
{
    if (!l)
        return 0;
    for (size_t k = 0; k < l->n; k++)
        if (!strcmp(l->e[k].path, path))
            return l->e[k].line;
    return 0;
}

int scene_has(const scene_locator *l, const char *path) { return scene_line(l, path) > 0; }

const char *scene_syntax_error(const scene_locator *l, int *line)
{
    *line = scene_line(l, "#error");
    return *line > 0 ? l->problem : NULL;
}
