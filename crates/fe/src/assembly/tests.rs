//! The element passes against a plain element-by-element assembly.

use super::*;
use crate::beam::{corotational_beam_chord, Section};
use crate::model::{LineSpec, Segment, Support};

/// A 23-element line (not a multiple of the four lanes), pinned at the top and fixed at the
/// anchor, bent into a shape with every kind of element: the ends' (some dofs prescribed) and
/// interior ones, and one chord laid from the top pointing along −x (the angle wrap's side).
fn bent_line() -> (LineModel, Placement, Vec<f64>) {
    let seg = |length, element_length| {
        Segment::uniform(
            length,
            element_length,
            Section {
                ea: 3.4e9,
                ei: 17.7e6,
            },
            1010.0,
            145.0,
            0.2286,
        )
    };
    let model = LineModel::build(&LineSpec {
        segments: vec![seg(40.0, 4.0), seg(13.0, 1.0)],
        top: Support::Pinned,
        anchor: Support::Fixed,
        seabed: None,
        flexjoint: Some((5.0e5, 0.1)),
    })
    .expect("model");
    let n = model.nodes();
    let mut q = vec![0.0; 3 * n];
    for i in 0..n {
        let s = model.arc[i];
        q[3 * i] = -s * (0.02 * s).cos();
        q[3 * i + 1] = 60.0 - s * (0.03 * s).sin();
        q[3 * i + 2] = -std::f64::consts::PI + 0.01 * s;
    }
    let u = (0..3 * n)
        .map(|g| 1e-3 * ((g * 7919) % 113) as f64 - 0.05)
        .collect();
    (model, Placement::new(&q), u)
}

/// The residual and tangent as a plain element-by-element assembly forms them: zeros, then
/// each element's forces and stiffness added in element order ([`corotational_beam_chord`]).
fn plain(model: &LineModel, pl: &Placement, u: &[f64], asm: &Assembler) -> (Vec<f64>, Vec<f64>) {
    let mut r = vec![0.0; 3 * model.nodes()];
    let mut k = vec![0.0; asm.k.values.len()];
    for (e, el) in model.elements.iter().enumerate() {
        let b = 3 * e;
        let [cx, cz] = pl.chords[e];
        let resp = corotational_beam_chord(
            cx + (u[b + 3] - u[b]),
            cz + (u[b + 4] - u[b + 1]),
            pl.base[b + 2] + u[b + 2],
            pl.base[b + 5] + u[b + 5],
            el.l0,
            &el.section,
            true,
        );
        for a in 0..6 {
            r[b + a] += resp.force[a];
        }
        let (pairs, len) = &asm.elem_pairs[e];
        for &(t, s) in &pairs[..*len as usize] {
            let (i, j) = UPPER_PAIRS[t as usize];
            k[s] += resp.stiffness[i][j];
        }
    }
    (r, k)
}

#[test]
fn element_passes_are_the_plain_assembly_to_the_bit() {
    let (model, pl, u) = bent_line();
    let mut asm = Assembler::new(&model).expect("assembler");
    let ne = model.elements.len();
    // Every element whose six dofs are free and whose neighbours' are too takes the common
    // offsets; the ends' do not.
    let regular = asm.elem_base.iter().filter(|b| **b != NONE).count();
    assert!(regular >= ne - 3, "{regular} of {ne} elements regular");
    assert!(asm.elem_base[0] == NONE && asm.elem_base[ne - 1] == NONE);
    let (r, k) = plain(&model, &pl, &u, &asm);
    let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    asm.residual.fill(f64::NAN);
    asm.assemble_element_forces(&pl, &u, 0..ne);
    assert_eq!(bits(&asm.residual), bits(&r), "forces only");
    asm.residual.fill(f64::NAN);
    asm.k.clear();
    asm.assemble_elements_with_tangent(&pl, &u, 0..ne);
    assert_eq!(bits(&asm.residual), bits(&r), "forces with the tangent");
    assert_eq!(bits(&asm.k.values), bits(&k), "tangent");
}

/// The structure assembled over two parts of the line (elements `0..=K` and `K..`, the element
/// across the boundary in both) gives each part's own nodes (`0..=K`, `K+1..`) the whole line's
/// residual and tangent columns to the bit, at every boundary `K` of the bent line (its ends, the
/// flexjoint's node and both segments, every place modulo the four lanes), with and without the
/// tangent; a part leaves the other part's tangent columns alone.
#[test]
fn parts_of_the_line_are_the_whole_to_the_bit() {
    let (model, pl, u) = bent_line();
    let ne = model.elements.len();
    let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    let mut whole = Assembler::new(&model).expect("assembler");
    let eqs = |nodes: std::ops::Range<usize>| {
        let e: Vec<usize> = model.equation[3 * nodes.start..3 * nodes.end]
            .iter()
            .filter_map(|e| *e)
            .collect();
        e.first().copied().unwrap_or(0)..e.last().map_or(0, |l| l + 1)
    };
    let slots =
        |a: &Assembler, cols: std::ops::Range<usize>| a.k.values[a.k.column_slots(cols)].to_vec();
    for with_k in [false, true] {
        whole.assemble_structure(&model, &pl, &u, 0.01, with_k);
        for k in 1..ne - 1 {
            for (elements, nodes) in [(0..k + 1, 0..k + 1), (k..ne, k + 1..ne + 1)] {
                let mut part = Assembler::new(&model).expect("assembler");
                part.residual.fill(f64::NAN);
                part.k.values.fill(f64::NAN);
                part.assemble_structure_part(&model, &pl, &u, (0.01, with_k), elements.clone());
                let dofs = 3 * nodes.start..3 * nodes.end;
                assert_eq!(
                    bits(&part.residual[dofs.clone()]),
                    bits(&whole.residual[dofs]),
                    "boundary {k}, elements {elements:?}, tangent {with_k}"
                );
                let cols = eqs(nodes.clone());
                if with_k {
                    assert_eq!(
                        bits(&slots(&part, cols.clone())),
                        bits(&slots(&whole, cols)),
                        "boundary {k}, elements {elements:?}: tangent"
                    );
                    let other = if nodes.start == 0 {
                        eqs(k + 2..ne + 1)
                    } else {
                        eqs(0..k)
                    };
                    assert!(
                        slots(&part, other).iter().all(|v| v.is_nan()),
                        "boundary {k}: the other part's columns untouched"
                    );
                } else {
                    assert!(part.k.values.iter().all(|v| v.is_nan()));
                }
            }
        }
    }
}
