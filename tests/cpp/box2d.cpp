// The pieces of a glass plate and of a mud run as Box2D bodies (Debian's libbox2d-dev, Box2D
// 2.4): one dynamic body per fragment or cell, one fixture per convex piece
// (hibi_convex_pieces, at most b2_maxPolygonVertices = 8 points each). Checks that the
// bodies' masses at density 1 (mass = area) add up to the plate's area, then steps the world
// with the bodies falling on the ground and checks that every position stays finite. The
// pieces start in contact along every crack; they collide with the ground only (a filter
// group), as a shattering effect often has them.
//
// Box2D welds points closer than half b2_linearSlop and refuses (asserts on) a piece left
// with fewer than 3 points or no area; such slivers are counted, with their area, and left
// out, as an engine would.
#include <box2d/box2d.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "hibi.h"

#define CHECK(cond)                                                                                                  \
    do {                                                                                                             \
        if (!(cond)) {                                                                                               \
            std::printf("failed: %s (line %d)\n", #cond, __LINE__);                                                  \
            std::exit(1);                                                                                            \
        }                                                                                                            \
    } while (0)

// Builds the bodies of rings/points scaled by `scale` (metres per unit), checks the masses
// against `area` (the plate's, in units²) and steps the world.
static void bodies(const char *what, const std::vector<hibi_ring> &rings, const std::vector<hibi_vec2> &points,
                   double area, float scale) {
    size_t scratch_len = 0, triangle_count = 0, piece_count = 0, written = 0;
    CHECK(hibi_pieces_scratch_size(rings.data(), rings.size(), points.data(), points.size(), &scratch_len) == HIBI_OK);
    std::vector<uint32_t> scratch(scratch_len);
    CHECK(hibi_pieces_counts(rings.data(), rings.size(), points.data(), points.size(), scratch.data(), scratch.size(),
                             &triangle_count, &piece_count) == HIBI_OK);
    std::vector<hibi_convex_piece> pieces(piece_count);
    CHECK(hibi_convex_pieces(rings.data(), rings.size(), points.data(), points.size(), scratch.data(), scratch.size(),
                             pieces.data(), pieces.size(), &written) == HIBI_OK &&
          written == piece_count);

    b2World world(b2Vec2(0.0f, -10.0f));
    b2BodyDef ground_def;
    b2Body *ground = world.CreateBody(&ground_def);
    b2PolygonShape ground_box;
    ground_box.SetAsBox(1000.0f, 1.0f, b2Vec2(0.0f, -2.0f), 0.0f);
    ground->CreateFixture(&ground_box, 0.0f);

    std::vector<b2Body *> body_of(rings.size(), nullptr);
    size_t body_count = 0, fixtures = 0, dropped = 0;
    double dropped_area = 0.0;
    const float weld = 0.5f * b2_linearSlop;
    for (const hibi_convex_piece &piece : pieces) {
        b2Vec2 v[b2_maxPolygonVertices];
        int32 n = 0;
        double twice = 0.0;
        CHECK(piece.point_count >= 3 && piece.point_count <= b2_maxPolygonVertices);
        for (uint32_t k = 0; k < piece.point_count; k++) {
            hibi_vec2 p = points[piece.points[k]], q = points[piece.points[(k + 1) % piece.point_count]];
            twice += (double)p.x * q.y - (double)q.x * p.y;
            b2Vec2 w(p.x * scale, p.y * scale);
            bool unique = true;
            for (int32 j = 0; j < n; j++) unique = unique && b2DistanceSquared(w, v[j]) >= weld * weld;
            if (unique) v[n++] = w;
        }
        // What Box2D takes: 3 or more points after welding, spanning an area well above
        // FLT_EPSILON (m²), which b2PolygonShape::Set asserts.
        double welded = 0.0;
        for (int32 j = 0; j < n; j++) welded += (double)b2Cross(v[j], v[(j + 1) % n]);
        if (n < 3 || welded / 2.0 < 1e-5) {
            dropped++;
            dropped_area += twice / 2.0;
            continue;
        }
        b2Body *&body = body_of[piece.ring];
        if (body == nullptr) {
            b2BodyDef def;
            def.type = b2_dynamicBody;
            body = world.CreateBody(&def);
            body_count++;
        }
        b2PolygonShape shape;
        shape.Set(v, n);
        b2FixtureDef fixture;
        fixture.shape = &shape;
        fixture.density = 1.0f;
        // With the ground only: the plate's pieces touching along the cracks make ~210 000
        // contacts a step otherwise.
        fixture.filter.groupIndex = -1;
        body->CreateFixture(&fixture);
        fixtures++;
    }
    // Density 1: a body's mass is its area in m².
    double mass = 0.0;
    size_t outer_rings = 0;
    for (size_t i = 0; i < rings.size(); i++) {
        outer_rings += rings[i].hole_of == HIBI_RING_NOT_A_HOLE;
        if (body_of[i] != nullptr) {
            b2MassData data;
            body_of[i]->GetMassData(&data);
            mass += data.mass;
        }
    }
    double ratio = mass / ((double)scale * scale) / area;
    CHECK(body_count == outer_rings);
    CHECK(std::fabs(ratio - 1.0) <= 1e-4 && dropped_area <= 1e-4 * area);
    float lowest = 1e30f;
    for (int step = 0; step < 120; step++) world.Step(1.0f / 60.0f, 8, 3);
    bool finite = true;
    for (b2Body *body : body_of) {
        if (body == nullptr) continue;
        b2Vec2 p = body->GetPosition();
        finite = finite && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(body->GetAngle());
        if (p.y < lowest) lowest = p.y;
    }
    CHECK(finite);
    std::printf("%s: %zu bodies for %zu polygons, %zu fixtures from %zu convex pieces (%zu slivers Box2D welds "
                "away, %.2g of the area), masses / plate area = %.6f, 120 steps: positions finite: yes, fell: %s\n",
                what, body_count, outer_rings, fixtures, piece_count, dropped, dropped_area / area, ratio,
                lowest < -0.5f ? "yes" : "no");
}

int main() {
    {
        hibi_glass_params p = hibi_glass_params_default();
        hibi_glass *glass = nullptr;
        hibi_glass_progress progress{};
        size_t scratch_size = 0, ring_count = 0, point_count = 0, rw = 0, pw = 0;
        CHECK(hibi_glass_create(&p, &glass) == HIBI_OK);
        while (!progress.finished) CHECK(hibi_glass_step(glass, 100000, &progress) == HIBI_OK);
        CHECK(hibi_glass_scratch_size(glass, &scratch_size) == HIBI_OK);
        std::vector<uint64_t> scratch(scratch_size / 8 + 1);
        CHECK(hibi_glass_fragment_counts(glass, scratch.data(), scratch_size, &ring_count, &point_count) == HIBI_OK);
        std::vector<hibi_ring> rings(ring_count);
        std::vector<hibi_vec2> points(point_count);
        CHECK(hibi_glass_fragments(glass, scratch.data(), scratch_size, rings.data(), ring_count, points.data(),
                                   point_count, &rw, &pw) == HIBI_OK);
        // 64 px to the metre: the default 640 x 480 plate is 10 m x 7.5 m.
        bodies("glass", rings, points, (double)p.width * p.height, 1.0f / 64.0f);
        hibi_glass_destroy(glass);
    }
    {
        hibi_mud_params p = hibi_mud_params_default();
        hibi_mud *mud = nullptr;
        hibi_mud_progress progress{};
        hibi_vec2 extent{};
        size_t ring_count = 0, point_count = 0, wrapping = 0, rw = 0, pw = 0;
        p.columns = 40;
        p.rows = 40;
        CHECK(hibi_mud_create(&p, &mud) == HIBI_OK);
        while (!progress.finished) CHECK(hibi_mud_step(mud, 1000000, &progress) == HIBI_OK);
        CHECK(hibi_mud_cell_counts(mud, &ring_count, &point_count, &wrapping) == HIBI_OK && wrapping == 0);
        std::vector<hibi_ring> rings(ring_count);
        std::vector<hibi_vec2> points(point_count);
        CHECK(hibi_mud_cells(mud, rings.data(), ring_count, points.data(), point_count, &rw, &pw) == HIBI_OK);
        CHECK(hibi_mud_extent(mud, &extent) == HIBI_OK);
        // A quarter metre per lattice unit: the 40-column plate is 10 m wide.
        bodies("mud", rings, points, (double)extent.x * extent.y, 0.25f);
        hibi_mud_destroy(mud);
    }
    return 0;
}
