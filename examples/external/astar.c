/* A* on an occupancy grid behind pathzoo's planner protocol (docs/external-planners.md).
 *
 * Reads the problem (one JSON object) on standard input and writes one JSON
 * answer on standard output. Eight-connected moves between cell centres,
 * diagonal moves only between two free orthogonal neighbours (no corner
 * cutting), octile heuristic, a binary heap. Moving obstacles, terrain and
 * parameters are ignored: this is a static shortest path.
 *
 * The JSON reading is minimal: it finds the few keys it needs and reads the
 * numbers after them in order, which is all pathzoo's problem requires.
 * Build: cc -O2 -o astar astar.c -lm
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char *read_all(FILE *in) {
    size_t cap = 1 << 16, len = 0, got;
    char *buf = malloc(cap + 1);
    while (buf && (got = fread(buf + len, 1, cap - len, in)) > 0) {
        len += got;
        if (len == cap) buf = realloc(buf, (cap *= 2) + 1);
    }
    if (buf) buf[len] = '\0';
    return buf;
}

/* The text right after "key": in the top-level object (keys are unique in a problem). */
static const char *value_of(const char *json, const char *key) {
    char pattern[64];
    snprintf(pattern, sizeof pattern, "\"%s\":", key);
    const char *at = strstr(json, pattern);
    return at ? at + strlen(pattern) : NULL;
}

/* Read n numbers starting at *p, skipping brackets, commas and spaces. */
static int read_numbers(const char **p, double *out, long n) {
    for (long i = 0; i < n; i++) {
        while (**p && strchr("[], \n\r\t", **p)) (*p)++;
        char *end;
        out[i] = strtod(*p, &end);
        if (end == *p) return -1;
        *p = end;
    }
    return 0;
}

/* occupancy given as the path of an .npy file of uint8 (large maps). */
static int read_npy(const char *value, unsigned char *cells, long n) {
    char path[4096];
    const char *end = strchr(value + 1, '"');
    if (!end || end - value - 1 >= (long)sizeof path) return -1;
    memcpy(path, value + 1, end - value - 1);
    path[end - value - 1] = '\0';
    FILE *f = fopen(path, "rb");
    if (!f) return -1;
    unsigned char head[10];
    if (fread(head, 1, 10, f) != 10) { fclose(f); return -1; }
    long header = head[6] == 1 ? head[8] | head[9] << 8 : -1;
    if (header < 0 || fseek(f, 10 + header, SEEK_SET) != 0 || fread(cells, 1, n, f) != (size_t)n) {
        fclose(f);
        return -1;
    }
    fclose(f);
    return 0;
}

typedef struct { double f; long node; } Item;

static void push(Item *heap, long *size, Item item) {
    long i = (*size)++;
    while (i > 0 && heap[(i - 1) / 2].f > item.f) { heap[i] = heap[(i - 1) / 2]; i = (i - 1) / 2; }
    heap[i] = item;
}

static Item pop(Item *heap, long *size) {
    Item top = heap[0], last = heap[--(*size)];
    long i = 0;
    for (;;) {
        long c = 2 * i + 1;
        if (c >= *size) break;
        if (c + 1 < *size && heap[c + 1].f < heap[c].f) c++;
        if (heap[c].f >= last.f) break;
        heap[i] = heap[c];
        i = c;
    }
    heap[i] = last;
    return top;
}

static int fail(const char *why) {
    fprintf(stderr, "astar: %s\n", why);
    return 1;
}

int main(void) {
    char *json = read_all(stdin);
    if (!json) return fail("out of memory");
    const char *p;
    double shape[2], cell, start[2], goal[2];
    if (!(p = value_of(json, "shape")) || read_numbers(&p, shape, 2)) return fail("no shape");
    if (!(p = value_of(json, "cell_size")) || read_numbers(&p, &cell, 1)) return fail("no cell_size");
    if (!(p = value_of(json, "start")) || read_numbers(&p, start, 2)) return fail("no start");
    if (!(p = value_of(json, "goal")) || read_numbers(&p, goal, 2)) return fail("no goal");
    long rows = (long)shape[0], cols = (long)shape[1], n = rows * cols;
    unsigned char *blocked = malloc(n), *closed = calloc(n, 1);
    double *g = malloc(n * sizeof *g), *value = malloc(n * sizeof *value);
    long *parent = malloc(n * sizeof *parent);
    Item *heap = malloc(8 * n * sizeof *heap + sizeof *heap);
    if (!blocked || !closed || !g || !value || !parent || !heap) return fail("out of memory");
    if (!(p = value_of(json, "occupancy"))) return fail("no occupancy");
    if (*p == '"') {
        if (read_npy(p, blocked, n)) return fail("cannot read the occupancy file");
    } else {
        if (read_numbers(&p, value, n)) return fail("bad occupancy");
        for (long i = 0; i < n; i++) blocked[i] = value[i] != 0.0;
    }
    long s = (long)floor(start[1] / cell) * cols + (long)floor(start[0] / cell);
    long t = (long)floor(goal[1] / cell) * cols + (long)floor(goal[0] / cell);
    double gr = floor(goal[1] / cell), gc = floor(goal[0] / cell);
    for (long i = 0; i < n; i++) { g[i] = INFINITY; parent[i] = -1; }
    long size = 0, expanded = 0;
    g[s] = 0.0;
    push(heap, &size, (Item){0.0, s});
    static const int dr[8] = {-1, 1, 0, 0, -1, -1, 1, 1}, dc[8] = {0, 0, -1, 1, -1, 1, -1, 1};
    while (size > 0) {
        Item it = pop(heap, &size);
        long u = it.node, r = u / cols, c = u % cols;
        if (u == t) break;
        if (closed[u]) continue; /* an older, worse entry of a node already expanded */
        closed[u] = 1;
        expanded++;
        for (int k = 0; k < 8; k++) {
            long rr = r + dr[k], cc = c + dc[k];
            if (rr < 0 || cc < 0 || rr >= rows || cc >= cols || blocked[rr * cols + cc]) continue;
            if (dr[k] && dc[k] && (blocked[r * cols + cc] || blocked[rr * cols + c])) continue;
            long v = rr * cols + cc;
            double cost = g[u] + (dr[k] && dc[k] ? M_SQRT2 : 1.0);
            if (cost < g[v]) {
                g[v] = cost;
                parent[v] = u;
                double dy = fabs(rr - gr), dx = fabs(cc - gc);
                double h = (dx > dy ? dx - dy : dy - dx) + M_SQRT2 * (dx < dy ? dx : dy);
                push(heap, &size, (Item){cost + h, v});
            }
        }
    }
    if (!isfinite(g[t])) {
        printf("{\"status\":\"no_path\",\"iterations\":1,\"evaluations\":1,\"message\":\"%ld cells expanded\"}\n", expanded);
        return 0;
    }
    long count = 0;
    for (long v = t; v != -1; v = parent[v]) value[count++] = (double)v;
    printf("{\"status\":\"solved\",\"iterations\":1,\"evaluations\":1,\"message\":\"%ld cells expanded\",\"path\":[[%.17g,%.17g]", expanded,
           start[0], start[1]);
    for (long i = count - 1; i >= 0; i--) {
        long v = (long)value[i];
        double x = (v % cols + 0.5) * cell, y = (v / cols + 0.5) * cell;
        if ((i == count - 1 && x == start[0] && y == start[1]) || (i == 0 && x == goal[0] && y == goal[1])) continue;
        printf(",[%.17g,%.17g]", x, y);
    }
    printf(",[%.17g,%.17g]],\"history\":[[1,1,%.17g]]}\n", goal[0], goal[1], g[t] * cell);
    return 0;
}
