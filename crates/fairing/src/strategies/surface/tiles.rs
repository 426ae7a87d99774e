//! The tiled order of the automatic step ([`SweepOrder::Tiles`](super::SweepOrder::Tiles)):
//! the paper's order (z_ij at the step's start, largest first, ties by index; Zhang–Cheng
//! §4.4 step 2.3) kept inside square tiles of [`TILE`] × [`TILE`] nodes, the tiles taken in
//! the order of their largest z.
//!
//! Why: a move reads and writes only its own windows (~45 nodes along its u-line and its
//! v-line), so the moves of far-apart points do not see each other, and the paper's global
//! order matters only between points whose windows cross. Visiting the grid tile by tile
//! keeps a tile's data (its nodes and the windows' halo, ~1 MB at [`TILE`] = 64) in the
//! processor's cache while its moves run, where the global order sends every move to a
//! scattered place of a grid that outgrew the cache. On a net of at most [`TILE`] nodes in
//! each direction there is one tile and the order is the paper's, bit for bit.

/// Nodes along each side of a tile: 64 × 64 nodes and a window's halo on each side are some
/// 7 400 nodes of ~160 bytes (points, originals, jumps, z bounds, tangents, radii), ~1.2 MB,
/// within the 2–4 MB of second-level cache of current server cores.
pub(super) const TILE: usize = 64;

/// The tiled order of one step, tile by tile: each tile's movable nodes (`movable(i, j)`)
/// sorted by their z (`z(k)`, k = i·`v_count` + j, read at the step's start) descending,
/// ties by index, into `nodes` (flat indices) one run per tile (the tiles row by row);
/// `runs` then lists those runs in the order of their first node (their largest z, ties by
/// index). The runs taken in `runs`' order are the paper's sorted order regrouped tile by
/// tile ([`regroup`] of the whole grid's sort, bit for bit), without sorting or moving the
/// whole grid's pairs: each tile's nodes are read in rows of [`TILE`] and sorted with their
/// z while they are in cache (the whole grid's radix sort and regrouping were some ten
/// passes over an array of 16 bytes a node, from memory at 400 × 400), and only the sorted
/// indices are kept (8 bytes a node, written once and read once by the step). `tile` and
/// `scratch` are reused storage. O(m·n).
#[allow(clippy::too_many_arguments)]
pub(super) fn tiled_order(
    u_count: usize,
    v_count: usize,
    z: impl Fn(usize) -> f64,
    movable: impl Fn(usize, usize) -> bool,
    nodes: &mut Vec<usize>,
    runs: &mut Vec<std::ops::Range<usize>>,
    tile: &mut Vec<(f64, usize)>,
    scratch: &mut Vec<(f64, usize)>,
) {
    nodes.clear();
    runs.clear();
    for i0 in (0..u_count).step_by(TILE) {
        for j0 in (0..v_count).step_by(TILE) {
            tile.clear();
            for i in i0..(i0 + TILE).min(u_count) {
                let row = i * v_count;
                tile.extend(
                    (j0..(j0 + TILE).min(v_count))
                        .filter(|&j| movable(i, j))
                        .map(|j| (z(row + j), row + j)),
                );
            }
            if tile.is_empty() {
                continue;
            }
            // Given in ascending index, the stable sort breaks ties by index.
            super::radix::sort_descending(tile, scratch);
            runs.push(nodes.len()..nodes.len() + tile.len());
            nodes.extend(tile.iter().map(|&(_, k)| k));
        }
    }
    // A run's first pair, its z read again (the same value).
    let first = |run: &std::ops::Range<usize>| {
        let k = nodes[run.start];
        (z(k), k)
    };
    runs.sort_unstable_by(|a, b| {
        let (a, b) = (first(a), first(b));
        b.0.total_cmp(&a.0).then(a.1.cmp(&b.1))
    });
}

/// The whole grid's sorted `order` (pairs (z, flat index), z descending, ties by index)
/// regrouped tile by tile: the tiles in the order of their first pair, each tile's pairs
/// in their order in `order` (a stable counting sort on the tile's rank). The reference
/// [`tiled_order`] is tested against (the run's own order until it). O(len + tiles).
#[cfg(test)]
fn regroup(order: &mut Vec<(f64, usize)>, u_count: usize, v_count: usize) {
    let tiles_u = u_count.div_ceil(TILE);
    let tiles_v = v_count.div_ceil(TILE);
    if tiles_u * tiles_v < 2 || order.len() < 2 {
        return;
    }
    let tile_of = |k: usize| (k / v_count / TILE) * tiles_v + (k % v_count) / TILE;
    // Each tile's rank (by its first appearance) and the count of its pairs.
    const UNSEEN: usize = usize::MAX;
    let mut rank = vec![UNSEEN; tiles_u * tiles_v];
    let mut counts: Vec<usize> = Vec::with_capacity(rank.len());
    for &(_, k) in order.iter() {
        let tile = tile_of(k);
        if rank[tile] == UNSEEN {
            rank[tile] = counts.len();
            counts.push(0);
        }
        counts[rank[tile]] += 1;
    }
    // Start of each rank's run.
    let mut next = Vec::with_capacity(counts.len());
    let mut sum = 0;
    for c in counts {
        next.push(sum);
        sum += c;
    }
    let mut scratch = vec![(0.0, 0); order.len()];
    for &item in order.iter() {
        let r = rank[tile_of(item.1)];
        scratch[next[r]] = item;
        next[r] += 1;
    }
    *order = scratch;
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Sorted (z descending, ties by index) pairs of a `u` × `v` grid with hashed z.
    fn sorted_grid(u: usize, v: usize) -> Vec<(f64, usize)> {
        let mut items: Vec<(f64, usize)> = (0..u * v)
            .map(|k| {
                let x = ((k * 7919 + 13) as f64 * 12.9898).sin() * 43_758.545_3;
                (((x - x.floor()) * 4.0).floor(), k)
            })
            .collect();
        items.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        items
    }

    #[test]
    fn one_tile_keeps_the_papers_order() {
        for (u, v) in [(1, 1), (13, 13), (TILE, TILE), (TILE, 3), (2, TILE)] {
            let sorted = sorted_grid(u, v);
            let mut order = sorted.clone();
            regroup(&mut order, u, v);
            assert_eq!(order, sorted, "{u} × {v}");
        }
    }

    #[test]
    fn tiles_are_contiguous_ordered_by_their_largest_z_and_keep_the_order_inside() {
        let (u, v) = (2 * TILE + 5, TILE + 1);
        let sorted = sorted_grid(u, v);
        let mut order = sorted.clone();
        regroup(&mut order, u, v);
        // The same pairs.
        let mut a = order.clone();
        let mut b = sorted.clone();
        a.sort_by_key(|p| p.1);
        b.sort_by_key(|p| p.1);
        assert_eq!(a, b);
        let tile = |k: usize| ((k / v) / TILE, (k % v) / TILE);
        // Each tile is one run; the runs come in the order of the tiles' first pair in the
        // sorted order; inside a run the sorted order is kept.
        type Run = ((usize, usize), Vec<(f64, usize)>);
        let mut runs: Vec<Run> = Vec::new();
        for &p in &order {
            match runs.last_mut() {
                Some((t, run)) if *t == tile(p.1) => run.push(p),
                _ => runs.push((tile(p.1), vec![p])),
            }
        }
        assert_eq!(runs.len(), 3 * 2, "every tile one run");
        let mut first_seen: Vec<(usize, usize)> = Vec::new();
        for p in &sorted {
            if !first_seen.contains(&tile(p.1)) {
                first_seen.push(tile(p.1));
            }
        }
        assert_eq!(runs.iter().map(|r| r.0).collect::<Vec<_>>(), first_seen);
        for (t, run) in &runs {
            let inside: Vec<(f64, usize)> = sorted.iter().copied().filter(|p| tile(p.1) == *t).collect();
            assert_eq!(run, &inside);
        }
        // The first pair is still the step's largest z.
        assert_eq!(order[0], sorted[0]);
    }

    #[test]
    fn tiled_order_is_the_sorted_grid_regrouped() {
        // Hashed z with many ties, some nodes not movable (a border and a scatter), grids of
        // one tile, of partial tiles and of several, and a grid with an empty tile.
        let z_of = |k: usize| {
            let x = ((k * 7919 + 13) as f64 * 12.9898).sin() * 43_758.545_3;
            ((x - x.floor()) * 4.0).floor()
        };
        let (mut nodes, mut runs, mut tile, mut scratch) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for (u, v) in [
            (13, 13),
            (TILE, TILE),
            (TILE + 1, 3),
            (2 * TILE + 5, TILE + 1),
            (200, 150),
        ] {
            let movable = |i: usize, j: usize| {
                i > 0
                    && j > 0
                    && i + 1 < u
                    && j + 1 < v
                    && !(i * 31 + j * 17).is_multiple_of(11)
                    && !(i < TILE && j < TILE && u > 150)
            };
            let mut sorted: Vec<(f64, usize)> = (0..u * v)
                .filter(|&k| movable(k / v, k % v))
                .map(|k| (z_of(k), k))
                .collect();
            sorted.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
            regroup(&mut sorted, u, v);
            tiled_order(
                u,
                v,
                z_of,
                movable,
                &mut nodes,
                &mut runs,
                &mut tile,
                &mut scratch,
            );
            let tiled: Vec<usize> = runs
                .iter()
                .flat_map(|r| nodes[r.clone()].iter().copied())
                .collect();
            let expected: Vec<usize> = sorted.iter().map(|p| p.1).collect();
            assert_eq!(tiled, expected, "{u} × {v}");
            // One run per tile holding a movable node (the 200 × 150 grid's first tile holds
            // none, 65 × 3's second only the last row).
            let mut holding: Vec<(usize, usize)> =
                sorted.iter().map(|p| (p.1 / v / TILE, p.1 % v / TILE)).collect();
            holding.sort_unstable();
            holding.dedup();
            assert_eq!(runs.len(), holding.len(), "{u} × {v}");
            assert!(runs.iter().all(|r| !r.is_empty()));
        }
    }
}
