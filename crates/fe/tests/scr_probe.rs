use catena_fe::beam::Section;
use catena_fe::model::*;
use catena_fe::statics::*;
use catena_seabed::law::{Law, Seabed};
use catena_seabed::LinearSeabed;

#[test]
fn probe() {
    let ei = 17.69e6;
    let ea = 3.395e9;
    let seg = |length, el| Segment {
        length,
        element_length: el,
        section: Section { ea, ei },
        weight: 1010.0,
        mass: 144.8,
        od: 0.228,
    };
    for k in [100e3, 1000e3, 10000e3] {
        let spec = LineSpec {
            segments: vec![seg(1050.0, 5.0), seg(300.0, 0.5), seg(250.0, 5.0)],
            top: Support::Pinned,
            anchor: Support::Pinned,
            seabed: Some(SeabedContact {
                seabed: Seabed {
                    law: Law::Linear(LinearSeabed::new(0.228, k, 0.0).unwrap()),
                    buoyancy: None,
                },
                mudline_z: 0.0,
            }),
            flexjoint: None,
        };
        let model = LineModel::build(&spec).unwrap();
        let emb = static_embedment(&model, 1010.0).unwrap();
        let ends = EndPositions {
            top: (933.79, 980.0),
            anchor: (0.0, 0.114 - emb),
        };
        let q = catenary_seed(&model, &ends).unwrap();
        let pl = Placement::new(&q);
        let mut u = vec![0.0; q.len()];
        let mut ws = StaticWorkspace::new(&model).unwrap();
        let t = std::time::Instant::now();
        let rep = solve(&model, &pl, &mut u, &mut ws, &StaticOptions::default());
        println!("k={k} {:?} {:?}", rep, t.elapsed());
        let r = line_results(&model, &pl, &u, &mut ws, |_, p| 0.228 * k * p);
        let s = summarise(&r, (ws.residual[0], ws.residual[1]));
        println!("{s:?} emb {emb}");
    }
}
