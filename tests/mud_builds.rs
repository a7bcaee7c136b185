//! Mud's network and cells built in bounded steps (`NetworkBuild`, `CellBuild`): the same
//! bytes as `Mud::network` and `Mud::cells` on every lattice and boundary, finished or live,
//! whatever the budgets; no step over its budget by more than one documented piece; a build
//! that outlives the network it read starts over; short buffers refused by name.

use hibi_core::mud::{
    Boundary, CellBuild, Mud, MudBuffers, MudError, MudParams, NetworkBuild, NetworkBuildBuffers, NetworkEdge,
    NetworkPoint, NetworkVertex, Topology,
};
use hibi_core::polygon::Ring;

/// A network's vertices, edges and points.
type Network = (Vec<NetworkVertex>, Vec<NetworkEdge>, Vec<NetworkPoint>);

/// The network as `Mud::network` writes it.
fn network_whole(mud: &Mud) -> Network {
    let c = mud.network_counts();
    let mut out =
        (vec![Default::default(); c.vertices], vec![Default::default(); c.edges], vec![Default::default(); c.points]);
    mud.network(&mut out.0, &mut out.1, &mut out.2).unwrap();
    out
}

/// The cells as `Mud::cells` writes them.
fn cells_whole(mud: &Mud) -> (Vec<Ring>, Vec<[f32; 2]>) {
    let c = mud.cell_counts();
    let mut out = (vec![Ring::default(); c.rings], vec![[0.0; 2]; c.points]);
    mud.cells(&mut out.0, &mut out.1).unwrap();
    out
}

/// Bits of every float, so that equality is byte equality.
fn bits<T: core::fmt::Debug>(v: &[T]) -> String {
    format!("{v:?}")
}

/// Builds the network of `mud` in steps of `budget`; returns it and the largest step's work
/// over its budget, in units.
fn network_built(mud: &Mud, budget: u64) -> (Network, u64) {
    let mut store = mud.network_build_memory().allocate();
    let mut build = NetworkBuild::new(mud, store.buffers()).unwrap();
    let (mut over, mut before) = (0, 0);
    loop {
        let p = build.step(mud, budget).unwrap();
        over = over.max((p.work - before).saturating_sub(budget));
        before = p.work;
        if p.finished {
            assert_eq!(p.counts, mud.network_counts());
            break;
        }
        assert!(build.vertices().is_empty() && build.edges().is_empty(), "nothing read before the end");
    }
    ((build.vertices().to_vec(), build.edges().to_vec(), build.points().to_vec()), over)
}

/// Builds the cells of `mud` in steps of `budget`; returns them and the largest overrun.
fn cells_built(mud: &Mud, budget: u64) -> ((Vec<Ring>, Vec<[f32; 2]>), u64) {
    let mut store = mud.cell_build_memory().allocate();
    let mut build = CellBuild::new(mud, store.buffers()).unwrap();
    let (mut over, mut before) = (0, 0);
    loop {
        let p = build.step(mud, budget).unwrap();
        over = over.max((p.work - before).saturating_sub(budget));
        before = p.work;
        if p.finished {
            assert_eq!((p.counts.rings, p.counts.points), (mud.cell_counts().rings, mud.cell_counts().points));
            break;
        }
        assert!(build.rings().is_empty(), "nothing read before the end");
    }
    ((build.rings().to_vec(), build.points().to_vec()), over)
}

/// Every lattice and boundary, finished and cut short: the builds write what the whole
/// calls write, bit for bit, at budgets of 1, 97 and unbounded; the builds' memory holds
/// every network and cell set; a step overruns its budget by less than one piece (the
/// points of the cracks leaving one mesh cell, twice; nine times one ring's points).
#[test]
fn builds_write_what_the_whole_calls_write_in_bounded_steps() {
    let mut largest = [0u64; 2];
    for topology in [Topology::Hexagonal, Topology::Square, Topology::Irregular] {
        for boundary in [Boundary::Open, Boundary::Periodic] {
            for (seed, stop) in [(3, None), (7, Some(4_000_000u64)), (11, Some(1_000_000))] {
                let p = MudParams { columns: 40, rows: 36, topology, boundary, seed, ..MudParams::default() };
                let m = p.memory().unwrap();
                let (mut scalars, mut words) = (vec![0.0f32; m.scalars], vec![0u32; m.words]);
                let mut mud = Mud::new(&p, MudBuffers { scalars: &mut scalars, words: &mut words }).unwrap();
                match stop {
                    None => assert!(mud.run().unwrap().finished),
                    Some(work) => {
                        mud.step(work).unwrap();
                    }
                }
                let what = format!("{topology:?} {boundary:?} seed {seed} stop {stop:?}");
                let network = network_whole(&mud);
                let cells = cells_whole(&mud);
                let nm = mud.network_build_memory();
                assert!(network.0.len() <= nm.vertices && network.1.len() <= nm.edges && network.2.len() <= nm.points);
                let cm = mud.cell_build_memory();
                assert!(cells.0.len() <= cm.rings && cells.1.len() <= cm.points, "{what}");
                // The longest crack and the largest ring bound the pieces.
                let longest = network.1.iter().map(|e| u64::from(e.point_count)).max().unwrap_or(0);
                let largest_ring = cells.0.iter().map(|r| u64::from(r.point_count)).max().unwrap_or(0);
                for budget in [1, 97, u64::MAX] {
                    let (built, over) = network_built(&mud, budget);
                    assert_eq!(bits(&built.0), bits(&network.0), "{what}: vertices at budget {budget}");
                    assert_eq!(bits(&built.1), bits(&network.1), "{what}: edges at budget {budget}");
                    assert_eq!(bits(&built.2), bits(&network.2), "{what}: points at budget {budget}");
                    assert!(over < 1 + 2 * 3 * (longest + 2), "{what}: a network step overran by {over}");
                    largest[0] = largest[0].max(over);
                    let (built, over) = cells_built(&mud, budget);
                    assert_eq!(bits(&built.0), bits(&cells.0), "{what}: rings at budget {budget}");
                    assert_eq!(bits(&built.1), bits(&cells.1), "{what}: points at budget {budget}");
                    assert!(over < 1 + 9 * largest_ring.max(4 * 6), "{what}: a cell step overran by {over}");
                    largest[1] = largest[1].max(over);
                }
            }
        }
    }
    println!("largest overrun: network {} units, cells {} units", largest[0], largest[1]);
}

/// A build started on one network and stepped on a run whose network shown changed since
/// starts over and ends with the new network; short buffers are refused naming the elements
/// they need, and a build reads nothing before it is finished.
#[test]
fn a_build_of_a_network_that_changed_starts_over_and_short_buffers_are_refused() {
    let p = MudParams { columns: 32, rows: 32, seed: 5, ..MudParams::default() };
    let m = p.memory().unwrap();
    let (mut scalars, mut words) = (vec![0.0f32; m.scalars], vec![0u32; m.words]);
    let mut mud = Mud::new(&p, MudBuffers { scalars: &mut scalars, words: &mut words }).unwrap();
    while mud.shown_broken_springs() == 0 {
        mud.step(50_000).unwrap();
    }
    let mut store = mud.network_build_memory().allocate();
    let mut cell_store = mud.cell_build_memory().allocate();
    let mut build = NetworkBuild::new(&mud, store.buffers()).unwrap();
    let mut cell_build = CellBuild::new(&mud, cell_store.buffers()).unwrap();
    build.step(&mud, 10).unwrap();
    cell_build.step(&mud, 10).unwrap();
    let shown = mud.shown_broken_springs();
    assert!(mud.run().unwrap().finished);
    assert!(mud.shown_broken_springs() > shown);
    let p = build.step(&mud, u64::MAX).unwrap();
    assert!(p.finished && p.work < u64::MAX);
    let whole = network_whole(&mud);
    assert_eq!(bits(build.edges()), bits(&whole.1));
    assert_eq!(bits(build.points()), bits(&whole.2));
    assert!(cell_build.step(&mud, u64::MAX).unwrap().finished);
    assert_eq!(bits(cell_build.rings()), bits(&cells_whole(&mud).0));

    let need = mud.network_build_memory();
    let (mut v, mut e, mut pts) = (
        vec![NetworkVertex::default(); need.vertices],
        vec![NetworkEdge::default(); need.edges - 1],
        vec![NetworkPoint::default(); need.points],
    );
    let short = NetworkBuildBuffers { vertices: &mut v, edges: &mut e, points: &mut pts };
    assert_eq!(NetworkBuild::new(&mud, short).err(), Some(MudError::BufferTooSmall { needed: need.edges }));
}
