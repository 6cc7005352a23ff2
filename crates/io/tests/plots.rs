//! The run's large plots drawn on canvases made ahead (`catena_io::plot::Canvas`) are the plots
//! drawn on their own, pixel for pixel; the PNG encoder's files decode to those pixels; another
//! extension still goes to the image crate's encoder for it; the opaque grid is plotters' default
//! translucent grid as it looks on white.

use std::path::{Path, PathBuf};

use catena::run::{DynamicRun, RunOptions};
use catena_io::plot::{self, Canvas};

mod common;

/// 5 s of the heave benchmark, envelopes from the start.
fn short_heave() -> DynamicRun {
    let scene = common::heave_scene(&[("dynamic.duration", 5.0), ("dynamic.envelope_start", 0.0)]);
    catena::run::simulate(scene, &mut [], RunOptions::default()).expect("the run completes")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("catena-plots-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir.join(name)
}

/// The decoded RGB pixels of an image file, and its size.
fn pixels(path: &Path) -> (Vec<u8>, (u32, u32)) {
    let img = image::open(path)
        .unwrap_or_else(|e| panic!("{} decodes: {e}", path.display()))
        .to_rgb8();
    let size = img.dimensions();
    (img.into_raw(), size)
}

#[test]
fn plots_on_canvases_made_ahead_are_the_plots_drawn_on_their_own() {
    let r = short_heave();
    let own = scratch("dynamic-own.png");
    plot::dynamic(&own, &r).expect("dynamic.png");
    let (reference, size) = pixels(&own);
    assert_eq!(size, plot::DYNAMIC_SIZE);
    // Not a white page: the curves and the text are drawn.
    let inked = reference.iter().filter(|&&b| b < 128).count();
    assert!(inked > 10_000, "{inked} dark channel values");
    for (name, canvas) in [
        ("made", Some(Canvas::white(plot::DYNAMIC_SIZE))),
        ("larger", Some(Canvas::white(plot::RANGES_MAX_SIZE))),
        ("too small", Some(Canvas::white((100, 100)))),
    ] {
        let p = scratch(&format!("dynamic-{}.png", name.replace(' ', "-")));
        plot::dynamic_on(&p, &r, canvas).expect("dynamic.png on a canvas");
        assert!(pixels(&p) == (reference.clone(), size), "{name} canvas");
    }
    let own = scratch("ranges-own.png");
    plot::ranges(&own, &r).expect("ranges.png");
    let (reference, size) = pixels(&own);
    assert!(size.0 <= plot::RANGES_MAX_SIZE.0 && size.1 <= plot::RANGES_MAX_SIZE.1);
    let p = scratch("ranges-made.png");
    plot::ranges_on(&p, &r, Some(Canvas::white(plot::RANGES_MAX_SIZE))).expect("ranges.png");
    assert!(pixels(&p) == (reference, size), "ranges.png on a canvas");
}

#[test]
fn other_extensions_go_to_their_own_encoder_and_unknown_ones_are_refused() {
    let r = short_heave();
    let jpg = scratch("dynamic.jpg");
    plot::dynamic(&jpg, &r).expect("a JPEG");
    let bytes = std::fs::read(&jpg).expect("written");
    assert_eq!(&bytes[..2], &[0xFF, 0xD8], "a JPEG's magic number");
    assert_eq!(pixels(&jpg).1, plot::DYNAMIC_SIZE);
    let e = plot::dynamic(&scratch("dynamic.xyz"), &r).expect_err("no such format");
    assert!(e.to_string().contains("must end in .png"), "{e}");
    let e = plot::dynamic(&scratch("no/such/folder/dynamic.png"), &r).expect_err("no folder");
    assert!(
        e.to_string()
            .contains("cannot write the image: No such file or directory"),
        "{e}"
    );
}

/// `plot::GRID_BOLD` and `plot::GRID_LIGHT` are what plotters' default grid lines (black at 20 %
/// and 10 % opacity) blend to on a white canvas, along a row and down a column (the two ways a
/// line is blended), within the one level by which those two ways round differently.
#[test]
fn the_opaque_grid_is_the_default_translucent_grid_on_white() {
    use plotters::prelude::*;
    for (grey, alpha) in [(plot::GRID_BOLD, 0.2), (plot::GRID_LIGHT, 0.1)] {
        assert_eq!((grey.0, grey.1), (grey.1, grey.2), "a grey");
        let (w, h) = (40u32, 40u32);
        let mut px = vec![255u8; 3 * (w * h) as usize];
        {
            let root = BitMapBackend::with_buffer(&mut px, (w, h)).into_drawing_area();
            let style = BLACK.mix(alpha);
            root.draw(&PathElement::new(vec![(0, 10), (39, 10)], style))
                .expect("a row");
            root.draw(&PathElement::new(vec![(30, 0), (30, 39)], style))
                .expect("a column");
            root.present().expect("drawn");
        }
        let at = |x: u32, y: u32| px[3 * (y * w + x) as usize];
        for (x, y) in [(0, 10), (5, 10), (20, 10), (30, 3), (30, 30)] {
            let level = at(x, y);
            assert!(
                (i32::from(level) - i32::from(grey.0)).abs() <= 1,
                "alpha {alpha}: the line at ({x}, {y}) is {level} on white, the opaque grey {}",
                grey.0
            );
        }
        // Where the two translucent lines cross, the pixel is darker than either (the opaque grid
        // draws it in the one grey).
        assert!(at(30, 10) < at(20, 10));
    }
}
