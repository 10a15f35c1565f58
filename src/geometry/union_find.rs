//! Union–find over indices (`parent[i]` is i's parent; a root is its own): how faces
//! join triangles and convex parts join faces. A union puts the lesser root over the
//! greater, so every set's root is its least member, whatever order the unions come in
//! and however the paths are shortened: callers rely on that to list sets in the order
//! of their first members.

/// The root of `x`'s set: its least member. On the way each node is pointed at its
/// grandparent (path splitting), which changes no root.
pub(crate) fn find(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let p = parent[x as usize];
        parent[x as usize] = parent[p as usize];
        x = p;
    }
    x
}

/// Joins the sets of `a` and `b` under the lesser root.
pub(crate) fn union(parent: &mut [u32], a: u32, b: u32) {
    let ra = find(parent, a);
    let rb = find(parent, b);
    if ra != rb {
        parent[ra.max(rb) as usize] = ra.min(rb);
    }
}
