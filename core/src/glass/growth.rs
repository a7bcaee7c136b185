//! Growth by the sector rule (Agui et al. §4.2.2, Eqs. 12–19) and the stop rules (§4.2.3).

use super::grid::NONE;
use super::{CrackEnd, CrackKind, Edge, Glass, GlassProgress, wrap};
use crate::geom::{Intersection, Point, Segment};

/// What a step ran into.
enum Hit {
    /// Nothing: the tip moves the whole step.
    Nothing,
    /// The plate's edge, at this point.
    Edge([f32; 2]),
    /// Segment `edge`, at this point and parameter along the step.
    Crack { edge: u32, at: [f32; 2], along: f32 },
}

impl Glass<'_> {
    /// Advances growth by at most `budget` tip steps (at least one, unless finished).
    /// A time step advances every growing tip once, in crack order.
    pub fn step(&mut self, budget: u64) -> GlassProgress {
        let mut work = 0u64;
        while !self.finished && work < budget.max(1) {
            if self.cursor == 0 && !self.rebuild_tips() {
                self.finish();
                break;
            }
            if self.cursor < self.crack_count {
                let c = self.cracks[self.cursor];
                if c.growing && self.time >= c.wake {
                    self.advance(self.cursor);
                    work += 1;
                    if self.capacity_reached {
                        self.finish();
                    }
                }
                self.cursor += 1;
                continue;
            }
            self.cursor = 0;
            self.time += 1;
            // Generation ends when every large and ring crack of this impact has stopped.
            let impact = self.impacts - 1;
            let driving = self.cracks[..self.crack_count]
                .iter()
                .any(|c| c.growing && c.impact == impact && c.kind != CrackKind::Radial);
            if !driving || self.time >= self.time_limit {
                self.finish();
            }
        }
        self.progress()
    }

    /// Puts every growing tip into the tip grid; false if it is full.
    fn rebuild_tips(&mut self) -> bool {
        self.tips.clear();
        for i in 0..self.crack_count {
            let c = self.cracks[i];
            if c.growing {
                let (cx, cy, _, _) = self.grid.span(c.tip[0], c.tip[1], c.tip[0], c.tip[1]);
                if !self.tips.insert(cy * self.grid.columns + cx, i as u32) {
                    self.capacity_reached = true;
                    return false;
                }
            }
        }
        true
    }

    /// Whether `point` lies in the sector S ahead of a tip at `w` heading `direction`
    /// (angle φ, radius B), and its offset from `w` and distance.
    fn in_sector(&self, w: [f32; 2], direction: [f32; 2], point: [f32; 2]) -> Option<([f32; 2], f32)> {
        let e = [point[0] - w[0], point[1] - w[1]];
        let distance = libm::sqrtf(e[0] * e[0] + e[1] * e[1]);
        if distance == 0.0 || distance > self.params.sector_radius {
            return None;
        }
        let cosine = (e[0] * direction[0] + e[1] * direction[1]) / distance;
        (cosine >= self.sector_cosine).then_some((e, distance))
    }

    /// The bounding box (x0, y0, x1, y1) of the sector S ahead of a tip at `w` heading
    /// `direction`: its apex, the ends of its arc, and the arc's extremes along the axes that
    /// fall inside it.
    fn sector_box(&self, w: [f32; 2], direction: [f32; 2]) -> [f32; 4] {
        let b = self.params.sector_radius;
        let (c, s) = (self.sector_cosine, self.sector_sine);
        let mut bounds = [w[0], w[1], w[0], w[1]];
        let mut include = |d: [f32; 2]| {
            let q = [w[0] + b * d[0], w[1] + b * d[1]];
            bounds = [bounds[0].min(q[0]), bounds[1].min(q[1]), bounds[2].max(q[0]), bounds[3].max(q[1])];
        };
        let [dx, dy] = direction;
        include([dx * c - dy * s, dx * s + dy * c]);
        include([dx * c + dy * s, -dx * s + dy * c]);
        for axis in [[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]] {
            if axis[0] * dx + axis[1] * dy >= c {
                include(axis);
            }
        }
        bounds
    }

    /// Calls `visit` once with every segment filed in the grid cells covering the box
    /// [x0, x1] × [y0, y1] (a segment in several cells is visited once, by its stamp).
    fn segments_near(&mut self, x0: f32, y0: f32, x1: f32, y1: f32, mut visit: impl FnMut(&Self, u32)) {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.stamps.fill(0);
            self.stamp = 1;
        }
        let (cx0, cy0, cx1, cy1) = self.grid.span(x0, y0, x1, y1);
        for cy in cy0..=cy1 {
            for cx in cx0..=cx1 {
                let mut entry = self.segments.heads[cy * self.grid.columns + cx];
                while entry != NONE {
                    let e = self.segments.item[entry as usize];
                    if self.stamps[e as usize] != self.stamp {
                        self.stamps[e as usize] = self.stamp;
                        visit(self, e);
                    }
                    entry = self.segments.next[entry as usize];
                }
            }
        }
    }

    /// The endpoints of edge `e`.
    fn edge_points(&self, e: u32) -> ([f32; 2], [f32; 2]) {
        let edge = self.edges[e as usize];
        (self.vertices[edge.from as usize].at, self.vertices[edge.to as usize].at)
    }

    /// The sum F1 + F2 + F3 (+ the ring's pull to its circle) on crack `i`'s tip.
    fn force(&mut self, i: usize) -> [f32; 2] {
        let c = self.cracks[i];
        let p = self.params;
        let w = c.tip;
        let direction = [libm::cosf(c.heading), libm::sinf(c.heading)];
        let mut f = [0.0f32; 2];
        let [x0, y0, x1, y1] = self.sector_box(w, direction);
        // F1: away from every other tip in S, ∝ 1/r².
        let (cx0, cy0, cx1, cy1) = self.grid.span(x0, y0, x1, y1);
        for cy in cy0..=cy1 {
            for cx in cx0..=cx1 {
                self.tips.for_each(cy * self.grid.columns + cx, |j| {
                    if j as usize == i {
                        return;
                    }
                    if let Some((e, r)) = self.in_sector(w, direction, self.cracks[j as usize].tip) {
                        let k = p.tip_repulsion / (r * r * r);
                        f[0] -= k * e[0];
                        f[1] -= k * e[1];
                    }
                });
            }
        }
        // F2: towards every crack in S, along its normal (to meet it at a right angle), ∝ 1/d².
        let crack = i as u32;
        let mut pull = [0.0f32; 2];
        self.segments_near(x0, y0, x1, y1, |glass, e| {
            if glass.edges[e as usize].crack == crack {
                return;
            }
            let (a, z) = glass.edge_points(e);
            // Outside the sector's box: no point of it is in the sector.
            if a[0].max(z[0]) < x0 || a[0].min(z[0]) > x1 || a[1].max(z[1]) < y0 || a[1].min(z[1]) > y1 {
                return;
            }
            let q = Segment::new(Point::new(a[0], a[1]), Point::new(z[0], z[1])).closest_point(Point::new(w[0], w[1]));
            if let Some((v, d)) = glass.in_sector(w, direction, [q.x, q.y]) {
                let k = p.crack_attraction / (d * d * d);
                pull[0] += k * v[0];
                pull[1] += k * v[1];
            }
        });
        f[0] += pull[0];
        f[1] += pull[1];
        // F2 for the plate's edges.
        for q in [[0.0, w[1]], [p.width, w[1]], [w[0], 0.0], [w[0], p.height]] {
            if let Some((v, d)) = self.in_sector(w, direction, q) {
                let k = p.crack_attraction / (d * d * d);
                f[0] += k * v[0];
                f[1] += k * v[1];
            }
        }
        // F3: a unit force whose direction is a normal draw around the heading.
        let angle = c.heading + p.wander * self.forces.normal_f32();
        f[0] += libm::cosf(angle);
        f[1] += libm::sinf(angle);
        // Ring cracks keep to their circle: along it, plus back towards radius d.
        if matches!(c.kind, CrackKind::RingCounterClockwise | CrackKind::RingClockwise) {
            let (centre, radius) = c.ring;
            let rel = [w[0] - centre[0], w[1] - centre[1]];
            let r = libm::sqrtf(rel[0] * rel[0] + rel[1] * rel[1]).max(1e-6);
            let out = [rel[0] / r, rel[1] / r];
            let along = if c.kind == CrackKind::RingCounterClockwise { [-out[1], out[0]] } else { [out[1], -out[0]] };
            let back = (radius - r) / p.sector_radius;
            f[0] += p.ring_adherence * (along[0] + back * out[0]);
            f[1] += p.ring_adherence * (along[1] + back * out[1]);
        }
        f
    }

    /// One step of crack `i` (Eqs. 12–17), stopping exactly on a crack or the edge.
    fn advance(&mut self, i: usize) {
        let p = self.params;
        let f = self.force(i);
        let c = self.cracks[i];
        // Eqs. 12–15: turn towards F, at most θ_th, weighted by 1 − exp(−t/T).
        let difference = wrap(libm::atan2f(f[1], f[0]) - c.heading).clamp(-p.turn_limit, p.turn_limit);
        let weight = 1.0 - libm::expf(-(c.age as f32) / p.turn_delay);
        let heading = wrap(c.heading + difference * weight);
        // Eqs. 16–17: move by v·dt with dt = 1 step.
        let w = c.tip;
        let next = [w[0] + c.speed * libm::cosf(heading), w[1] + c.speed * libm::sinf(heading)];
        let tip_vertex = if c.last_segment == NONE { c.start_vertex } else { self.edges[c.last_segment as usize].to };
        let (hit, along) = self.first_hit(i, w, next);
        let time = self.time as f32;
        let (end, stop) = match hit {
            Hit::Nothing => (self.add_vertex(next), CrackEnd::Growing),
            Hit::Edge(at) => (self.add_vertex(at), CrackEnd::Edge),
            Hit::Crack { edge, at, along } => (self.meeting_vertex(edge, at, along), CrackEnd::Crack),
        };
        if end == NONE {
            return; // capacity reached; the caller finishes
        }
        if end == tip_vertex {
            // Met a crack exactly at its own tip (a rounding tie): it stops there.
            let c = &mut self.cracks[i];
            c.growing = false;
            c.end = CrackEnd::Crack;
            return;
        }
        let segment = Edge::new(tip_vertex, end, i as u32, [time, time + along]);
        let Some(e) = self.add_edge(segment) else { return };
        let closes_cycle = self.join(tip_vertex, end);
        let c = &mut self.cracks[i];
        c.tip = self.vertices[end as usize].at;
        c.heading = heading;
        c.age += 1;
        if stop != CrackEnd::Growing {
            c.growing = false;
            c.end = stop;
        }
        if closes_cycle {
            self.enclose(2 * e);
        }
    }

    /// The vertex where a tip meets edge `e` at point `at` (parameter `along` on the edge): one
    /// of its ends if it meets it there, else a new vertex that splits it. NONE when full.
    fn meeting_vertex(&mut self, e: u32, at: [f32; 2], along: f32) -> u32 {
        let edge = self.edges[e as usize];
        if along <= 0.0 || at == self.vertices[edge.from as usize].at {
            return edge.from;
        }
        if along >= 1.0 || at == self.vertices[edge.to as usize].at {
            return edge.to;
        }
        let v = self.add_vertex(at);
        if v != NONE && !self.split(e, v, along) {
            return NONE;
        }
        v
    }

    /// The first crack or edge the step from `w` to `next` meets, and where along the step
    /// (1 when it meets nothing).
    fn first_hit(&mut self, i: usize, w: [f32; 2], next: [f32; 2]) -> (Hit, f32) {
        let p = self.params;
        let own_last = self.cracks[i].last_segment;
        let path = Segment::new(Point::new(w[0], w[1]), Point::new(next[0], next[1]));
        // The plate's edge: where the step leaves [0, W] × [0, H], the crossed coordinate exact.
        let mut best = (Hit::Nothing, 1.0f32);
        for (axis, limit) in [(0usize, 0.0f32), (0, p.width), (1, 0.0), (1, p.height)] {
            let (from, to) = (w[axis], next[axis]);
            let outside = if limit == 0.0 { to < 0.0 } else { to > limit };
            if outside && from != to {
                let t = (limit - from) / (to - from);
                if t < best.1 {
                    let other = 1 - axis;
                    let mut at = [0.0; 2];
                    at[axis] = limit;
                    at[other] = w[other] + (next[other] - w[other]) * t;
                    best = (Hit::Edge(at), t);
                }
            }
        }
        let (x0, x1) = (w[0].min(next[0]), w[0].max(next[0]));
        let (y0, y1) = (w[1].min(next[1]), w[1].max(next[1]));
        let mut found = (NONE, best.1, [0.0f32; 2]);
        self.segments_near(x0, y0, x1, y1, |glass, e| {
            if e == own_last {
                return;
            }
            let (a, z) = glass.edge_points(e);
            // Boxes apart: no meeting.
            if a[0].max(z[0]) < x0 || a[0].min(z[0]) > x1 || a[1].max(z[1]) < y0 || a[1].min(z[1]) > y1 {
                return;
            }
            let other = Segment::new(Point::new(a[0], a[1]), Point::new(z[0], z[1]));
            let (t, at) = match path.intersect(other) {
                Intersection::None => return,
                Intersection::Point { point, along_first, .. } => (along_first, point),
                Intersection::Overlap { start, .. } => (path.closest_parameter(start), start),
            };
            if t > 0.0 && t < found.1 {
                found = (e, t, [at.x, at.y]);
            }
        });
        if found.0 != NONE {
            let along = found.1;
            let edge = found.0;
            let t_other = {
                let (a, z) = self.edge_points(edge);
                Segment::new(Point::new(a[0], a[1]), Point::new(z[0], z[1]))
                    .closest_parameter(Point::new(found.2[0], found.2[1]))
            };
            return (Hit::Crack { edge, at: found.2, along: t_other }, along);
        }
        best
    }

    /// Splits edge `e` at vertex `v` (a point on it at parameter `along`), so that the crack
    /// meeting it there shares the vertex. False when full.
    fn split(&mut self, e: u32, v: u32, along: f32) -> bool {
        let old = self.edges[e as usize];
        let time = old.time[0] + (old.time[1] - old.time[0]) * along;
        let tail = Edge { next: old.next, ..Edge::new(v, old.to, old.crack, [time, old.time[1]]) };
        let Some(t) = self.push_edge(tail) else { return false };
        // The head now ends at v: out of the old end's incidence list, into v's.
        self.unlink(old.to, e);
        let head = &mut self.edges[e as usize];
        head.to = v;
        head.next = t;
        head.time[1] = time;
        head.links[1] = self.vertices[v as usize].first_edge;
        head.orient(self.vertices[old.from as usize].at, self.vertices[v as usize].at);
        self.vertices[v as usize].first_edge = e;
        self.join(v, old.from);
        let owner = &mut self.cracks[old.crack as usize];
        if owner.last_segment == e {
            owner.last_segment = t;
        }
        true
    }

    /// Removes edge `e` from vertex `v`'s incidence list.
    fn unlink(&mut self, v: u32, e: u32) {
        let (previous, after) = {
            let g = self.crack_graph();
            let mut previous = NONE;
            let mut x = self.vertices[v as usize].first_edge;
            while x != e && x != NONE {
                previous = x;
                x = g.next_at(v, x);
            }
            (previous, g.next_at(v, e))
        };
        if previous == NONE {
            self.vertices[v as usize].first_edge = after;
        } else {
            let p = &mut self.edges[previous as usize];
            p.links[usize::from(p.from != v)] = after;
        }
    }

    /// Appends a new segment to its crack's chain; its index, or None when full.
    fn add_edge(&mut self, edge: Edge) -> Option<u32> {
        let crack = edge.crack as usize;
        let e = self.push_edge(edge)?;
        let c = &mut self.cracks[crack];
        if c.last_segment == NONE {
            c.first_segment = e;
        } else {
            self.edges[c.last_segment as usize].next = e;
        }
        self.cracks[crack].last_segment = e;
        Some(e)
    }

    /// Stores an edge, links it into its vertices' incidence lists and files it in the grid;
    /// None (capacity reached) when full.
    fn push_edge(&mut self, mut edge: Edge) -> Option<u32> {
        if self.edge_count == self.edges.len() {
            self.capacity_reached = true;
            return None;
        }
        let e = self.edge_count as u32;
        edge.links = [self.vertices[edge.from as usize].first_edge, self.vertices[edge.to as usize].first_edge];
        edge.orient(self.vertices[edge.from as usize].at, self.vertices[edge.to as usize].at);
        self.vertices[edge.from as usize].first_edge = e;
        self.vertices[edge.to as usize].first_edge = e;
        self.edges[self.edge_count] = edge;
        self.edge_count += 1;
        let (a, z) = self.edge_points(e);
        let (cx0, cy0, cx1, cy1) = self.grid.span(a[0].min(z[0]), a[1].min(z[1]), a[0].max(z[0]), a[1].max(z[1]));
        for cy in cy0..=cy1 {
            for cx in cx0..=cx1 {
                if !self.segments.insert(cy * self.grid.columns + cx, e) {
                    self.capacity_reached = true;
                    return None;
                }
            }
        }
        Some(e)
    }
}
