//! Property tests of the simulator's invariants and value-stability (golden) tests.

use fuzzymotiv::modelling::{Action, DEFAULT_ACTION_TOLERANCE};
use fuzzymotiv::random::{Rng, rng_from_seed, standard_normal, uniform01};
use fuzzymotiv::simulation::{Arena, RawTrial, TrialParams, run_trial};
use fuzzymotiv::simulation::{BUILTIN_ROOMS, Room};
use fuzzymotiv::simulation::{Mlp, MlpShape};
use fuzzymotiv::simulation::{Motion, RawRobot, wrap_angle};
use proptest::prelude::*;

/// Checked parameters: `trial`, a robot of `motion` and the default action tolerance.
fn params(trial: RawTrial, motion: Motion) -> TrialParams {
    let robot = RawRobot {
        motion,
        ..RawRobot::default()
    };
    TrialParams::from_raw(
        &trial,
        &robot,
        fuzzymotiv::simulation::RobotSpec::khepera(),
        DEFAULT_ACTION_TOLERANCE,
    )
    .unwrap()
}

fn genome(seed: u64, scale: f64) -> Vec<f64> {
    let mut rng = rng_from_seed(seed);
    (0..68)
        .map(|_| (2.0 * uniform01(&mut rng) - 1.0) * scale)
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// The robot never ends a step overlapping a wall, whatever the controller and room.
    #[test]
    fn robot_never_overlaps_a_wall(seed in any::<u64>(), room in 0usize..5, scale in 0.5f64..5.0, noise in 0.0f64..0.2, wheels in any::<bool>()) {
        let motion = if wheels { Motion::Wheels } else { Motion::Actions };
        let params = params(RawTrial { steps: 300, noise: Some(noise), ..RawTrial::default() }, motion);
        let arena = Arena::new(Room::builtin(BUILTIN_ROOMS[room]).unwrap(), &params);
        let mut mlp = Mlp::from_genome(MlpShape::default(), &genome(seed, scale)).unwrap();
        let tr = run_trial(&arena, &mut mlp, &mut rng_from_seed(seed ^ 1));
        for p in &tr.poses {
            let clearance = arena.walls().iter().map(|w| w.dist_to(p.position())).fold(f64::INFINITY, f64::min);
            prop_assert!(clearance >= params.robot().radius(), "pose {p:?} is {clearance} mm from a wall");
            prop_assert!(arena.room().contains(p.position()));
        }
    }
}

/// The e-puck2 in the paper's rooms, the Thymio II in the rooms scaled for it (rooms/thymio2).
fn robot_room(robot: usize, room: usize) -> (&'static fuzzymotiv::simulation::RobotSpec, Room) {
    const THYMIO_ROOMS: [(&str, &str); 2] = [
        ("H", include_str!("../../../../rooms/thymio2/H.toml")),
        (
            "square",
            include_str!("../../../../rooms/thymio2/square.toml"),
        ),
    ];
    match robot {
        0 => (
            fuzzymotiv::simulation::RobotSpec::builtin("epuck2").unwrap(),
            Room::builtin(BUILTIN_ROOMS[room]).unwrap(),
        ),
        _ => {
            let (name, text) = THYMIO_ROOMS[room % 2];
            let room = Room::from_toml_str(text, name).unwrap();
            (
                fuzzymotiv::simulation::RobotSpec::builtin("thymio2").unwrap(),
                room,
            )
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Every robot, whatever its sensors, never ends a step overlapping a wall or outside its
    /// room, with both motions: the e-puck2 (8 sensors reading 0–3731) and the Thymio II
    /// (7 sensors, a 160 mm disc).
    #[test]
    fn no_robot_overlaps_a_wall(seed in any::<u64>(), robot in 0usize..2, room in 0usize..5, scale in 0.5f64..5.0, wheels in any::<bool>()) {
        let motion = if wheels { Motion::Wheels } else { Motion::Actions };
        let (spec, room) = robot_room(robot, room);
        let raw = RawRobot { motion, ..RawRobot::default() };
        let trial = RawTrial { steps: 300, ..RawTrial::default() };
        let params = TrialParams::from_raw(&trial, &raw, spec, DEFAULT_ACTION_TOLERANCE).unwrap();
        let arena = Arena::new(room, &params);
        let shape = MlpShape::default().with_inputs(spec.sensors()).unwrap();
        let mut rng = rng_from_seed(seed);
        let g: Vec<f64> = (0..shape.genome_len()).map(|_| (2.0 * uniform01(&mut rng) - 1.0) * scale).collect();
        let mut mlp = Mlp::from_genome(shape, &g).unwrap();
        let tr = run_trial(&arena, &mut mlp, &mut rng_from_seed(seed ^ 1));
        prop_assert!(tr.sensors.iter().all(|s| s.len() == spec.sensors()));
        prop_assert!(tr.sensors.iter().flat_map(|s| s.iter()).all(|&v| (0.0..=spec.reading_max()).contains(&v)));
        for p in &tr.poses {
            let clearance = arena.walls().iter().map(|w| w.dist_to(p.position())).fold(f64::INFINITY, f64::min);
            prop_assert!(clearance >= params.robot().radius(), "pose {p:?} is {clearance} mm from a wall");
            prop_assert!(arena.room().contains(p.position()));
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Remembered sightings change nothing: a trial reads exactly what a trial that casts every
    /// ray reads, the first time a pose is seen and every time after, in every room.
    #[test]
    fn the_memo_changes_nothing(seed in any::<u64>(), room in 0usize..5, scale in 0.5f64..5.0, noise in 0.0f64..0.2) {
        let params = params(RawTrial { steps: 300, noise: Some(noise), ..RawTrial::default() }, Motion::Actions);
        let arena = Arena::new(Room::builtin(BUILTIN_ROOMS[room]).unwrap(), &params);
        let casting = arena.clone().without_memo();
        prop_assert!(arena.remembers() && !casting.remembers());
        let mut mlp = Mlp::from_genome(MlpShape::default(), &genome(seed, scale)).unwrap();
        let cast = run_trial(&casting, &mut mlp, &mut rng_from_seed(seed ^ 1));
        for _ in 0..2 {
            let remembered = run_trial(&arena, &mut mlp, &mut rng_from_seed(seed ^ 1));
            prop_assert_eq!(&remembered, &cast);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// With `actions` motion every heading stays on the 30° grid from home and every step moves
    /// the centre by 0 or exactly v_max·dt = 8 mm, for random controllers in every room.
    #[test]
    fn actions_stay_on_the_grid(seed in any::<u64>(), room in 0usize..5, scale in 0.5f64..5.0, noise in 0.0f64..0.2) {
        let params = params(RawTrial { steps: 300, noise: Some(noise), ..RawTrial::default() }, Motion::Actions);
        let arena = Arena::new(Room::builtin(BUILTIN_ROOMS[room]).unwrap(), &params);
        let mut mlp = Mlp::from_genome(MlpShape::default(), &genome(seed, scale)).unwrap();
        let tr = run_trial(&arena, &mut mlp, &mut rng_from_seed(seed ^ 1));
        let home = arena.room().home.heading;
        for (t, w) in tr.poses.windows(2).enumerate() {
            let k = wrap_angle(w[1].heading - home) / (std::f64::consts::PI / 6.0);
            prop_assert!((k - k.round()).abs() < 1e-9, "step {t}: heading {} off the grid", w[1].heading);
            let d = w[0].position().dist(w[1].position());
            prop_assert!(d == 0.0 || (d - 8.0).abs() < 1e-9, "step {t} moved {d} mm");
            let turned = w[0].heading != w[1].heading;
            prop_assert!(!(turned && d > 0.0), "step {t} both turned and moved");
            if tr.actions[t] == Action::Straight {
                prop_assert!(!turned);
            } else {
                prop_assert!(d == 0.0 && !tr.collisions[t]);
            }
        }
    }
}

/// A user room with an obstacle: the invariant holds there too.
#[test]
fn robot_never_overlaps_an_obstacle() {
    let room = Room::from_toml_str(
        "name='box'\noutline=[[0,0],[500,0],[500,500],[0,500]]\nhome={x=100,y=100,heading_deg=45}\n[[obstacles]]\noutline=[[200,200],[300,200],[300,300],[200,300]]",
        "box.toml",
    )
    .unwrap();
    let params = TrialParams::default();
    let arena = Arena::new(room, &params);
    for seed in 0..40 {
        let mut mlp = Mlp::from_genome(MlpShape::default(), &genome(seed, 3.0)).unwrap();
        let tr = run_trial(&arena, &mut mlp, &mut rng_from_seed(seed));
        for p in &tr.poses {
            assert!(
                arena
                    .walls()
                    .iter()
                    .all(|w| w.dist_to(p.position()) >= 27.5),
                "{p:?}"
            );
        }
    }
}

/// Pinned random streams: if a dependency bump changes these, every result changes.
#[test]
fn random_streams_are_value_stable() {
    let mut rng = rng_from_seed(42);
    let raw: Vec<u64> = (0..3).map(|_| rng.next_u64()).collect();
    let u = uniform01(&mut rng);
    let n = standard_normal(&mut rng);
    let got = format!("{raw:?} {u:.17} {n:.17}");
    assert_eq!(got, GOLDEN_STREAM, "the random stream changed");
}

/// Pinned short trajectory of the first release's model (`wheels` motion, no end at home, the
/// first release's H room; noise on): sensor → network → noise → arc kinematics.
#[test]
fn short_wheels_trajectory_is_value_stable() {
    let trial = RawTrial {
        steps: 60,
        end_at_home: false,
        ..RawTrial::default()
    };
    let params = params(trial, Motion::Wheels);
    let room = Room::from_toml_str(
        include_str!("../../../../rooms/first-release/H.toml"),
        "H.toml",
    )
    .unwrap();
    let arena = Arena::new(room, &params);
    let mut mlp = Mlp::from_genome(MlpShape::default(), &genome(7, 2.0)).unwrap();
    let tr = run_trial(&arena, &mut mlp, &mut rng_from_seed(7));
    let last = tr.poses.last().unwrap();
    let collisions = tr.collisions.iter().filter(|&&c| c).count();
    let got = format!(
        "{:.9} {:.9} {:.9} {collisions}",
        last.x, last.y, last.heading
    );
    assert_eq!(got, GOLDEN_WHEELS_TRAJECTORY, "the trajectory changed");
}

/// Pinned trajectory of the default model (`actions` motion, built-in H room, noise on): the
/// final pose, collisions, executed steps (this robot ends its trial at home after 251) and
/// the action counts (idle steps count as straight).
#[test]
fn actions_trajectory_is_value_stable() {
    let params = TrialParams::default();
    let arena = Arena::new(Room::builtin("H").unwrap(), &params);
    let mut mlp = Mlp::from_genome(MlpShape::default(), &genome(14, 3.0)).unwrap();
    let tr = run_trial(&arena, &mut mlp, &mut rng_from_seed(14));
    let last = tr.poses.last().unwrap();
    let collisions = tr.collisions.iter().filter(|&&c| c).count();
    let count = |a: Action| tr.actions.iter().filter(|&&x| x == a).count();
    let got = format!(
        "{:.9} {:.9} {:.9} {collisions} {} {}/{}/{}/{}",
        last.x,
        last.y,
        last.heading,
        tr.executed(),
        count(Action::Straight),
        count(Action::Left30),
        count(Action::Right30),
        count(Action::Turn180)
    );
    assert_eq!(got, GOLDEN_ACTIONS_TRAJECTORY, "the trajectory changed");
}

const GOLDEN_STREAM: &str = "[15021278609987233951, 5881210131331364753, 18149643915985481100] 0.70113559813475557 -1.51097498300067068";
const GOLDEN_WHEELS_TRAJECTORY: &str = "140.946894338 99.908383522 2.859619974 0";
const GOLDEN_ACTIONS_TRAJECTORY: &str = "34.143593539 150.276877527 -1.570796327 22 251 365/28/7/0";
