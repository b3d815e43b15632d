// The e-puck2 deployment kit of a genome file, for an e-puck2 as Enki models it
// (docs/robots-sources.md §1.3: wheel base 51 mm, 128 mm/s, IR response up to 3731), written
// into a directory: `.ci/run` compiles it for the e-puck2's Cortex-M4 against the firmware's
// header stubs (crates/fuzzymotiv/tests/data/epuck2-stubs) and prints its size.
// `fuzzymotiv export RUN --to c --target epuck2` writes the kit of a run evolved for the e-puck2
// with that robot's own values.
//
//     cargo run -p fuzzymotiv --example epuck2_kit -- best_genome.json OUT_DIR

use std::error::Error;
use std::path::PathBuf;

use fuzzymotiv::export::{ExportedController, KitRobot, epuck2_kit};
use fuzzymotiv::simulation::{MlpShape, TrialParams};

/// A genome file's network: `{"shape": {"hidden": H}, "weights": [...]}`.
#[derive(serde::Deserialize)]
struct Genome {
    shape: Shape,
    weights: Vec<f64>,
}

#[derive(serde::Deserialize)]
struct Shape {
    hidden: usize,
}

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [genome, out] = args.as_slice() else {
        return Err("usage: epuck2_kit GENOME.json OUT_DIR".into());
    };
    let genome: Genome = serde_json::from_slice(&std::fs::read(genome)?)?;
    let shape = MlpShape::with_hidden(genome.shape.hidden)?;
    let robot = KitRobot {
        name: "epuck2".into(),
        sensors: 8,
        reading_max: 3731.0,
        v_max: 128.0,
        wheel_base: 51.0,
        dt: 0.1,
        turn_deg: 30.0,
    };
    let controller = ExportedController::new(shape, &genome.weights, &TrialParams::default())?
        .for_robot(robot)?;
    let out = PathBuf::from(out);
    std::fs::create_dir_all(&out)?;
    for file in epuck2_kit(&controller).files {
        std::fs::write(out.join(&file.name), &file.contents)?;
        println!("{}", out.join(&file.name).display());
    }
    Ok(())
}
