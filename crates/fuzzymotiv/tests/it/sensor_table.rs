//! `trial.sensor_table`: a sensor table file read by the `sampled` model instead of the
//! built-in Khepera tables.

use fuzzymotiv::experiment::{RawConfig, RoomFile, RoomFiles, Setup, SetupError, UnreadableFile};
use fuzzymotiv::random::{rng_from_seed, uniform};
use fuzzymotiv::simulation::{
    Arena, Mlp, MlpShape, Motion, Pose, RawRobot, RawTrial, Room, SensorTable, TrialParams,
    run_trial,
};

/// One axis ray per sensor: 700 up to 10 mm, 300 up to 50 mm, nothing beyond.
const STEP: &str = "[[ray]]\ndistance_mm = [10, 50]\nreading = [700, 300]\n";

fn params(motion: Motion, noise: f64) -> TrialParams {
    let trial = RawTrial {
        noise: Some(noise),
        ..RawTrial::default()
    };
    let robot = RawRobot {
        motion,
        ..RawRobot::default()
    };
    let khepera = fuzzymotiv::simulation::RobotSpec::khepera();
    TrialParams::from_raw(&trial, &robot, khepera, 0.25).unwrap()
}

fn with_table(p: TrialParams, text: &str) -> TrialParams {
    p.with_sensor_table(SensorTable::from_toml_str(text, "t.toml").unwrap().intern())
}

#[test]
fn a_sensor_table_changes_the_readings_as_its_data_says() {
    let p = with_table(TrialParams::default(), STEP);
    let a = Arena::new(Room::builtin("square").unwrap(), &p);
    // Front sensors 2, 3 sit 24.5 mm ahead of the centre, facing the x = 800 wall.
    let at = |gap: f64| a.read_sensors(&Pose::new(800.0 - 24.5 - gap, 300.0, 0.0));
    let s = at(5.5);
    assert_eq!((s[2], s[3], s[6], s[7]), (700.0, 700.0, 0.0, 0.0));
    assert_eq!(at(10.0)[2], 700.0);
    assert_eq!(at(10.5)[2], 300.0);
    assert_eq!(at(50.0)[2], 300.0);
    assert_eq!(at(50.5)[2], 0.0);
    // The built-in tables read 1023 (three rays summed) at 5.5 mm.
    let built_in = Arena::new(Room::builtin("square").unwrap(), &TrialParams::default());
    assert_eq!(
        built_in.read_sensors(&Pose::new(770.0, 300.0, 0.0))[2],
        1023.0
    );
}

#[test]
fn the_khepera_table_as_a_file_reproduces_the_built_in_sensors() {
    let file = SensorTable::khepera().to_toml("the built-in Khepera tables");
    for motion in [Motion::Actions, Motion::Wheels] {
        let plain = params(motion, 0.06);
        let table = with_table(plain, &file);
        let shape = MlpShape::with_hidden(4).unwrap();
        for (k, room) in ["H", "T", "square"].into_iter().enumerate() {
            let mut g = rng_from_seed(k as u64);
            let genome: Vec<f64> = (0..shape.genome_len())
                .map(|_| uniform(&mut g, -3.0, 3.0))
                .collect();
            let run = |p: &TrialParams| {
                let arena = Arena::new(Room::builtin(room).unwrap(), p);
                let mut net = Mlp::from_genome(shape, &genome).unwrap();
                run_trial(&arena, &mut net, &mut rng_from_seed(7 + k as u64))
            };
            let (a, b) = (run(&plain), run(&table));
            assert_eq!(a.sensors, b.sensors, "{room} {motion:?}");
            assert_eq!(a.poses, b.poses, "{room} {motion:?}");
        }
    }
}

/// Finds one sensor table file, `robot.toml`.
struct TableFile(String);

impl RoomFiles for TableFile {
    fn find(&self, entry: &str) -> Result<Option<RoomFile>, UnreadableFile> {
        Ok((entry == "robot.toml").then(|| RoomFile {
            text: self.0.clone(),
            source_name: "/cfg/robot.toml".into(),
            entry: "/cfg/robot.toml".into(),
        }))
    }

    fn looked_for(&self, entry: &str) -> String {
        format!("/cfg/{entry}")
    }
}

fn resolve(config: &str, table: &str) -> Result<Setup, SetupError> {
    let raw = RawConfig::parse(config, "c.toml", &[]).unwrap();
    Setup::resolve(raw, "c.toml", &TableFile(table.to_string()))
}

#[test]
fn a_config_names_its_sensor_table_and_records_where_it_was_found() {
    let setup = resolve("[trial]\nsensor_table = \"robot.toml\"\n", STEP).unwrap();
    assert_eq!(
        setup.raw.trial.sensor_table.as_deref(),
        Some("/cfg/robot.toml")
    );
    assert!(
        setup
            .raw
            .to_toml()
            .contains("sensor_table = \"/cfg/robot.toml\"")
    );
    let e = resolve("[trial]\nsensor_table = \"nope.toml\"\n", STEP).unwrap_err();
    let text = e.to_string();
    assert!(
        text.starts_with("c.toml: field `trial.sensor_table`: no sensor table file \"nope.toml\""),
        "{text}"
    );
    // A config without a table writes no `sensor_table` key (earlier runs' configs unchanged).
    assert!(!RawConfig::default().to_toml().contains("sensor_table"));
}

#[test]
fn bad_sensor_tables_name_the_table_file_and_the_field() {
    let config = "[trial]\nsensor_table = \"robot.toml\"\n";
    let rising = "[[ray]]\ndistance_mm = [10, 50]\nreading = [300, 700]\n";
    let e = resolve(config, rising).unwrap_err().to_string();
    assert!(
        e.starts_with("/cfg/robot.toml: field `ray[0].reading`: must not increase"),
        "{e}"
    );
    let short = "[[ray]]\ndistance_mm = [10]\nreading = [300]\n";
    let e = resolve(config, short).unwrap_err().to_string();
    assert!(
        e.starts_with("/cfg/robot.toml: field `ray[0].distance_mm`: needs 2 to 64"),
        "{e}"
    );
    let e = resolve(config, "[[ray]\n").unwrap_err().to_string();
    assert!(
        e.starts_with("/cfg/robot.toml: not valid TOML (line 1"),
        "{e}"
    );
    let linear = "[trial]\nsensor_table = \"robot.toml\"\nsensor_model = \"linear\"\n";
    let e = resolve(linear, STEP).unwrap_err().to_string();
    assert!(
        e.starts_with(
            "c.toml: field `trial.sensor_table`: a sensor table is read by the \"sampled\""
        ),
        "{e}"
    );
}
