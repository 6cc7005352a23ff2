//! The linear seabed's lanes ([`super::linear_contact`]) against the node loop, on the test line of
//! `loads/tests.rs`.

use super::tests::{histories_at_rest, line, small_motion, N};
use super::*;
use catena_seabed::law::Law;
use catena_seabed::linear::LinearSeabed;

/// The linear seabed's contact a run of nodes at a time ([`linear_contact`]) gives the node loop's
/// residual, tangent, seabed forces and kept histories to the bit: with and without the law's
/// damping, with and without the tangent, nodes in contact and two clear of the mudline.
#[test]
fn linear_contact_lanes_are_the_node_loop_to_the_bit() {
    let (u, v) = small_motion();
    let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    for damping in [0.0, 3e3] {
        let law = Law::Linear(LinearSeabed::new(0.3, 2e5, damping).expect("linear"));
        let (model, pl) = line(law);
        let sb = model.seabed.as_ref().expect("seabed");
        let committed = histories_at_rest(&model, &pl);
        let m = LoadModel {
            line: &model,
            placement: &pl,
            hydro: None,
            structural_damping: None,
        };
        let at = Iterate {
            u: &u,
            v: &v,
            wave_kin: &[],
        };
        for with_k in [false, true] {
            let scale = TangentScale {
                with_k,
                k: 0.9,
                c_v: 40.0,
            };
            let run = |lanes: bool| {
                let mut asm = Assembler::new(&model).expect("assembler");
                let mut scratch = LoadScratch::new(N);
                asm.residual.fill(0.0);
                asm.k.clear();
                let mut kept = vec![sb.seabed.untouched(); N];
                let pass = SeabedPass::Trial {
                    committed: &committed,
                    anchors: &[],
                    dt: 0.1,
                    memo: &mut [],
                    keep: Some(&mut kept),
                };
                let force = &mut scratch.seabed_force;
                if lanes {
                    let part = (&mut force[..], &mut scratch.contact, &(0..N));
                    add_seabed(&m, &at, pass, scale, &mut asm, part);
                } else {
                    seabed_loops::<false>(&m, &at, pass, scale, &mut asm, (force, &(0..N)));
                }
                (asm, scratch.seabed_force, kept)
            };
            let ((a, fa, ka), (b, fb, kb)) = (run(true), run(false));
            let what = format!("damping {damping}, tangent {with_k}");
            assert_eq!(bits(&a.residual), bits(&b.residual), "{what}: residual");
            assert_eq!(bits(&a.k.values), bits(&b.k.values), "{what}: tangent");
            assert_eq!(bits(&fa), bits(&fb), "{what}: seabed force");
            assert_eq!(ka, kb, "{what}: kept histories");
            assert!(
                fa.iter().filter(|f| **f > 0.0).count() >= 8,
                "{what}: in contact"
            );
            assert!(fa.contains(&0.0), "{what}: a node clear of the mudline");
        }
    }
}
