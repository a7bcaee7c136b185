/*
 * Pieces for a physics engine from C: the fragments of a glass plate and the cells of a mud
 * run become triangles and convex pieces (hibi_pieces_scratch_size, hibi_pieces_counts,
 * hibi_triangulate, hibi_convex_pieces). Checks: every triangle counter-clockwise, every
 * convex piece strictly convex with 3 to HIBI_PIECE_MAX_POINTS points; each polygon's pieces
 * add up to its outer ring's area minus its holes', and a plate's to its size (glass width x height, the mud domain's extent); a short
 * output buffer is refused by name with nothing written.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hibi.h"

static double twice_area(hibi_vec2 a, hibi_vec2 b, hibi_vec2 c) {
    return ((double)b.x - a.x) * ((double)c.y - a.y) - ((double)b.y - a.y) * ((double)c.x - a.x);
}

#define CHECK(cond)                                                                                                  \
    do {                                                                                                             \
        if (!(cond)) {                                                                                               \
            printf("failed: %s (line %d)\n", #cond, __LINE__);                                                       \
            exit(1);                                                                                                 \
        }                                                                                                            \
    } while (0)

/* Cuts the pieces of rings/points and prints the worst relative area error of a polygon and
 * the summed area of all pieces. */
static void pieces(const char *what, const hibi_ring *rings, size_t ring_count, const hibi_vec2 *points,
                   size_t point_count, double expected_total) {
    size_t scratch_len = 0, triangle_count = 0, piece_count = 0, written = 777, i, k;
    uint32_t *scratch;
    hibi_triangle *triangles;
    hibi_convex_piece *convex;
    double *by_triangle = calloc(ring_count, sizeof(double)), *by_piece = calloc(ring_count, sizeof(double));
    double worst = 0.0, total = 0.0;
    unsigned bad = 0, most = 0;
    CHECK(hibi_pieces_scratch_size(rings, ring_count, points, point_count, &scratch_len) == HIBI_OK);
    scratch = malloc(scratch_len * sizeof(uint32_t));
    CHECK(hibi_pieces_counts(rings, ring_count, points, point_count, scratch, scratch_len, &triangle_count,
                             &piece_count) == HIBI_OK);
    triangles = malloc(triangle_count * sizeof(hibi_triangle));
    convex = malloc(piece_count * sizeof(hibi_convex_piece));
    CHECK(triangle_count > 0 && piece_count > 0 && piece_count <= triangle_count);
    /* One entry short: refused, named, nothing written. */
    memset(convex, 0xAB, piece_count * sizeof(hibi_convex_piece));
    CHECK(hibi_convex_pieces(rings, ring_count, points, point_count, scratch, scratch_len, convex, piece_count - 1,
                             &written) == HIBI_ERROR_BUFFER_TOO_SMALL);
    CHECK(strcmp(hibi_error_argument(), "pieces") == 0 && written == 777);
    for (i = 0; i < piece_count * sizeof(hibi_convex_piece); i++) CHECK(((unsigned char *)convex)[i] == 0xAB);
    CHECK(hibi_triangulate(rings, ring_count, points, point_count, scratch, scratch_len, triangles, triangle_count,
                           &written) == HIBI_OK && written == triangle_count);
    CHECK(hibi_convex_pieces(rings, ring_count, points, point_count, scratch, scratch_len, convex, piece_count,
                             &written) == HIBI_OK && written == piece_count);
    for (i = 0; i < triangle_count; i++) {
        const uint32_t *t = triangles[i].points;
        double a = twice_area(points[t[0]], points[t[1]], points[t[2]]);
        bad += a <= 0.0;
        by_triangle[triangles[i].ring] += a / 2.0;
    }
    for (i = 0; i < piece_count; i++) {
        const hibi_convex_piece *p = &convex[i];
        uint32_t n = p->point_count;
        CHECK(n >= 3 && n <= HIBI_PIECE_MAX_POINTS);
        if (n > most) most = n;
        for (k = 0; k < n; k++) {
            hibi_vec2 u = points[p->points[k]], v = points[p->points[(k + 1) % n]], w = points[p->points[(k + 2) % n]];
            bad += twice_area(u, v, w) <= 0.0;
            by_piece[p->ring] += ((double)u.x * v.y - (double)v.x * u.y) / 2.0;
        }
    }
    for (i = 0; i < ring_count; i++) {
        double want = rings[i].area;
        if (rings[i].hole_of != HIBI_RING_NOT_A_HOLE) continue;
        for (k = 0; k < ring_count; k++)
            if (rings[k].hole_of == i) want += rings[k].area;
        worst = fmax(worst, fmax(fabs(by_triangle[i] - want), fabs(by_piece[i] - want)) / rings[i].area);
        total += by_piece[i];
    }
    CHECK(bad == 0 && worst <= 1e-6);
    CHECK(fabs(total - expected_total) <= 1e-4 * expected_total);
    printf("%s: %u polygons' pieces add up: yes, %u triangles, %u convex pieces of at most %u points, "
           "all counter-clockwise and convex: yes\n",
           what, (unsigned)ring_count, (unsigned)triangle_count, (unsigned)piece_count, most);
    free(by_triangle);
    free(by_piece);
    free(scratch);
    free(triangles);
    free(convex);
}

static void glass(void) {
    hibi_glass_params p = hibi_glass_params_default();
    hibi_glass *glass = NULL;
    hibi_glass_progress progress = {0};
    size_t scratch_size = 0, ring_count = 0, point_count = 0, rw = 0, pw = 0;
    void *scratch;
    hibi_ring *rings;
    hibi_vec2 *points;
    p.seed = 7;
    CHECK(hibi_glass_create(&p, &glass) == HIBI_OK);
    while (!progress.finished) CHECK(hibi_glass_step(glass, 100000, &progress) == HIBI_OK);
    CHECK(hibi_glass_scratch_size(glass, &scratch_size) == HIBI_OK);
    scratch = malloc(scratch_size);
    CHECK(hibi_glass_fragment_counts(glass, scratch, scratch_size, &ring_count, &point_count) == HIBI_OK);
    rings = malloc(ring_count * sizeof(hibi_ring));
    points = malloc(point_count * sizeof(hibi_vec2));
    CHECK(hibi_glass_fragments(glass, scratch, scratch_size, rings, ring_count, points, point_count, &rw, &pw) ==
          HIBI_OK);
    pieces("glass", rings, ring_count, points, point_count, (double)p.width * p.height);
    free(scratch);
    free(rings);
    free(points);
    hibi_glass_destroy(glass);
}

static void mud(void) {
    hibi_mud_params p = hibi_mud_params_default();
    hibi_mud *mud = NULL;
    hibi_mud_progress progress = {0};
    size_t ring_count = 0, point_count = 0, wrapping = 0, rw = 0, pw = 0;
    hibi_vec2 extent = {0, 0};
    hibi_ring *rings;
    hibi_vec2 *points;
    p.columns = 40;
    p.rows = 40;
    p.seed = 3;
    CHECK(hibi_mud_create(&p, &mud) == HIBI_OK);
    while (!progress.finished) CHECK(hibi_mud_step(mud, 1000000, &progress) == HIBI_OK);
    CHECK(hibi_mud_cell_counts(mud, &ring_count, &point_count, &wrapping) == HIBI_OK);
    rings = malloc(ring_count * sizeof(hibi_ring));
    points = malloc(point_count * sizeof(hibi_vec2));
    CHECK(hibi_mud_cells(mud, rings, ring_count, points, point_count, &rw, &pw) == HIBI_OK);
    /* An open plate: the cells cover the domain. */
    CHECK(hibi_mud_extent(mud, &extent) == HIBI_OK && wrapping == 0);
    pieces("mud", rings, ring_count, points, point_count, (double)extent.x * extent.y);
    free(rings);
    free(points);
    hibi_mud_destroy(mud);
}

int main(void) {
    glass();
    mud();
    return 0;
}
