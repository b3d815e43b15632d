//! The Aseba program of a controller: the fixed-point network ([`super::quant`]), the control
//! loop (`wheels` motion: a `timer0` every control period; `actions` motion: the network at
//! the first `prox` event after the previous action, the action executed by odometry at the
//! 100 Hz `motor` event), the test events `fm_test`/`fm_run`, and the .aesl file around it.

use super::quant::{self, ONE, QUnit};
use crate::export::ExportedController;
use crate::simulation::robot::Motion;

/// The default speed of a target unit: the playground's `500 ↔ 16.6 cm/s`, 0.332 mm/s per
/// unit = 332 µm/s (the documentation's 500 ≈ 20 cm/s would be 400).
pub(crate) const UM_PER_UNIT: i64 = 332;

/// Where the program reads its readings: the target's variable and its length.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Source {
    /// The target's array variable, e.g. `prox.horizontal`.
    pub var: &'static str,
    /// Its length (7 on the Thymio II).
    pub len: usize,
}

/// The Thymio II's horizontal proximity sensors.
pub(crate) const THYMIO_PROX: Source = Source {
    var: "prox.horizontal",
    len: 7,
};

/// A generated program: the node's code, the `<constant>`s and the global events it uses.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct AeslProgram {
    /// The Aseba code of the node.
    pub code: String,
    /// Named constants (name, value), as the .aesl's `<constant>`s.
    pub constants: Vec<(String, i64)>,
    /// Global events (name, argument words).
    pub events: Vec<(String, usize)>,
    /// The network's inputs (N) and hidden units (H).
    pub n: usize,
    /// Hidden units.
    pub h: usize,
    /// The per-unit quantisation (hidden units, then the two outputs).
    pub units: Vec<QUnit>,
}

/// `values` as Aseba array-constructor lines (12 to a line).
fn list(values: impl IntoIterator<Item = i64>) -> String {
    let v: Vec<String> = values.into_iter().map(|x| x.to_string()).collect();
    v.chunks(12)
        .map(|c| c.join(", "))
        .collect::<Vec<_>>()
        .join(",\n    ")
}

fn decl(name: &str, values: Vec<i64>, comment: &str) -> String {
    format!(
        "# {comment}\nvar {name}[{}] = [{}]\n",
        values.len(),
        list(values)
    )
}

/// The network's sizes and the per-unit quantisation of `c`: N from the robot, H from the
/// shape; rows in the genome's order.
fn quantised(c: &ExportedController, r_max: i64) -> (usize, usize, Vec<QUnit>) {
    let (n, h) = (c.robot().sensors, c.shape().hidden());
    let (hidden_w, out_w) = c.weights().split_at((h * (n + 1)).min(c.weights().len()));
    let hidden = hidden_w
        .chunks_exact(n + 1)
        .map(|row| quant::quantise_row(row, r_max));
    let outputs = out_w
        .chunks_exact(h + 1)
        .map(|row| quant::quantise_row(row, i64::from(ONE)));
    (n, h, hidden.chain(outputs).collect())
}

/// The variable declarations: constants of the network, then working variables.
fn declarations(n: usize, h: usize, units: &[QUnit], motion: Motion) -> String {
    let weights = |range: std::ops::Range<usize>| -> Vec<i64> {
        units[range]
            .iter()
            .flat_map(|u| u.weights.iter().map(|&w| i64::from(w)))
            .collect()
    };
    let per_unit = |f: fn(&QUnit) -> i16| units.iter().map(|u| i64::from(f(u))).collect();
    let mut s = String::new();
    s += &decl(
        "fm_wh",
        weights(0..h),
        "hidden units: per unit [bias, w from input 1..N] as round(w * 2^(e+12) / reading_max)",
    );
    s += &decl(
        "fm_wo",
        weights(h..h + 2),
        "outputs (left, right): per output [bias, w from hidden 1..H] as round(w * 2^e)",
    );
    s += &decl(
        "fm_sh",
        per_unit(|u| u.shift),
        "per unit (hidden, then outputs): math.dot shift e + 12 - L (sum in Q L)",
    );
    s += &decl(
        "fm_lo",
        per_unit(|u| -u.bound),
        "per unit: sum clamp -8.0 in Q L",
    );
    s += &decl(
        "fm_hi",
        per_unit(|u| u.bound),
        "per unit: sum clamp +8.0 in Q L",
    );
    s += &decl(
        "fm_up",
        per_unit(|u| u.up),
        "per unit: factor 2^(10 - L) from Q L to Q10",
    );
    let table = quant::logistic_table()
        .into_iter()
        .map(|t| i64::from(t) - 2048)
        .collect();
    s += &decl(
        "fm_t",
        table,
        "logistic: round(4096 / (1 + exp(-i/16))) - 2048, i = 0..128, then the last again",
    );
    s += &format!(
        "# readings: clamp bounds (0 and reading_max = 1.0), the readings the network sees\n\
         # (sensors 0..N-1), the inputs (x[0] = 1.0 for the bias), the hidden activations in Q12\n\
         # (h[0] = 1.0 for the bias); filled at start\n\
         var fm_rlo[{n}]\nvar fm_rmax[{n}]\nvar fm_raw[{n}]\nvar fm_x[{}]\nvar fm_h[{}]\n",
        n + 1,
        h + 1
    );
    s += &format!(
        "# working variables: sums (Q10 after scaling), motor outputs m (Q12), 2m - 1 (Q12),\n\
         # wheel targets, action (0 straight, 1 left30, 2 right30, 3 turn180)\n\
         var fm_s[{}]\nvar fm_m[2] = [2048, 2048]\nvar fm_a[2] = [0, 0]\n\
         var fm_p\nvar fm_tgt[2] = [0, 0]\nvar fm_act = 0\nvar fm_u\nvar fm_y\nvar fm_k\nvar fm_j\n\
         # network evaluations so far; 1 while stopped by fm_test\n\
         var fm_count = 0\nvar fm_paused = 0\n\
         # 1: emit fm_state [readings, left target, right target] at each decision\n\
         var fm_monitor = 0\nvar fm_log[{}]\n",
        h + 2,
        n + 2
    );
    if motion == Motion::Actions {
        s += "# actions: executing one (1/0), what is left of it (units of FM_UM_PER_UNIT/6250 mm),\n\
              # wheel travel not yet counted (target units x 10 ms), wheel target at v_max,\n\
              # 10 ms ticks since the action started\n\
              var fm_busy = 0\nvar fm_todo = 0\nvar fm_sub = 0\nvar fm_vt = 0\nvar fm_ticks = 0\n";
    }
    s
}

/// `sub fm_sigma`: `fm_y` = σ(`fm_u`) in Q12 for `fm_u` in Q10 on [−8, 8].
fn sigma_sub() -> String {
    let k = quant::TABLE_SHIFT;
    let mask = (1 << k) - 1;
    format!(
        "# fm_y = logistic(fm_u) in Q12 for fm_u in Q10 (|fm_u| <= 8192): table at steps of 1/16 and\n\
         # linear interpolation; logistic(-u) = 1 - logistic(u)\n\
         sub fm_sigma\n\
         fm_y = abs(fm_u)\n\
         fm_k = fm_y >> {k}\n\
         fm_y = fm_t[fm_k] + (((fm_t[fm_k + 1] - fm_t[fm_k]) * (fm_y & {mask})) >> {k})\n\
         if fm_u < 0 then\n  fm_y = 2048 - fm_y\nelse\n  fm_y = 2048 + fm_y\nend\n"
    )
}

/// `sub fm_network`: the network on `fm_raw`, then the wheel targets and the action label.
fn network_sub(n: usize, h: usize) -> String {
    let mut s = String::from(
        "# the network on fm_raw: inputs, hidden units, outputs, wheel targets, action label\n\
         sub fm_network\n",
    );
    s += &format!("call math.clamp(fm_x[1:{n}], fm_raw, fm_rlo, fm_rmax)\n");
    for j in 0..h {
        let a = j * (n + 1);
        s += &format!(
            "call math.dot(fm_s[{j}], fm_wh[{a}:{}], fm_x, fm_sh[{j}])\n",
            a + n
        );
    }
    let last = h - 1;
    s += &format!(
        "call math.clamp(fm_s[0:{last}], fm_s[0:{last}], fm_lo[0:{last}], fm_hi[0:{last}])\n\
         call math.mul(fm_s[0:{last}], fm_s[0:{last}], fm_up[0:{last}])\n\
         for fm_j in 0:{last} do\n  fm_u = fm_s[fm_j]\n  callsub fm_sigma\n  fm_h[fm_j + 1] = fm_y\nend\n"
    );
    for o in 0..2 {
        let a = o * (h + 1);
        s += &format!(
            "call math.dot(fm_s[{}], fm_wo[{a}:{}], fm_h, fm_sh[{}])\n",
            h + o,
            a + h,
            h + o
        );
    }
    let (o0, o1) = (h, h + 1);
    s += &format!(
        "call math.clamp(fm_s[{o0}:{o1}], fm_s[{o0}:{o1}], fm_lo[{o0}:{o1}], fm_hi[{o0}:{o1}])\n\
         call math.mul(fm_s[{o0}:{o1}], fm_s[{o0}:{o1}], fm_up[{o0}:{o1}])\n"
    );
    for (o, side) in [(0, o0), (1, o1)] {
        s += &format!("fm_u = fm_s[{side}]\ncallsub fm_sigma\nfm_m[{o}] = fm_y\n");
    }
    s += "# wheel target = (2m - 1) * v_max / (FM_UM_PER_UNIT / 1000 mm/s per unit)\n";
    for o in 0..2 {
        s += &format!(
            "fm_a[{o}] = 2 * fm_m[{o}] - 4096\n\
             call math.muldiv(fm_p, fm_a[{o}], FM_V_MAX_DMM, 4096)\n\
             call math.muldiv(fm_tgt[{o}], fm_p, 100, FM_UM_PER_UNIT)\n"
        );
    }
    s += "# the action label from s = 2m - 1: both < 0 turn180; sR - sL > tolerance left30;\n\
          # sL - sR > tolerance right30; else straight\n\
          if fm_a[0] < 0 and fm_a[1] < 0 then\n  fm_act = 3\n\
          elseif fm_a[1] - fm_a[0] > FM_TOLERANCE then\n  fm_act = 1\n\
          elseif fm_a[0] - fm_a[1] > FM_TOLERANCE then\n  fm_act = 2\n\
          else\n  fm_act = 0\nend\n\
          fm_count = fm_count + 1\n";
    s
}

/// `if fm_monitor == 1`: emit `fm_state` with the readings and the wheel targets set.
fn monitor(n: usize) -> String {
    format!(
        "  if fm_monitor == 1 then\n    call math.copy(fm_log[0:{}], fm_raw)\n    \
         fm_log[{n}] = motor.left.target\n    fm_log[{}] = motor.right.target\n    \
         emit fm_state fm_log\n  end\n",
        n - 1,
        n + 1
    )
}

/// Subs and handlers executing actions (`actions` motion).
fn actions_code(read: &str, monitor: &str) -> String {
    let mut s = String::from(
        "# start executing fm_act: wheel travel to go, in units of FM_UM_PER_UNIT/6250 mm\n\
         sub fm_start\nfm_sub = 0\nfm_ticks = 0\nfm_busy = 1\n",
    );
    let arms = [
        ("FM_STRAIGHT_DMM", "fm_vt", "fm_vt"),
        ("FM_TURN_DMM", "-fm_vt", "fm_vt"),
        ("FM_TURN_DMM", "fm_vt", "-fm_vt"),
        ("FM_TURN180_DMM", "-fm_vt", "fm_vt"),
    ];
    for (k, (dist, left, right)) in arms.iter().enumerate() {
        let head = match k {
            0 => "if fm_act == 0 then".to_string(),
            3 => "else".to_string(),
            _ => format!("elseif fm_act == {k} then"),
        };
        s += &format!(
            "{head}\n  call math.muldiv(fm_todo, {dist}, 625, FM_UM_PER_UNIT)\n  \
             motor.left.target = {left}\n  motor.right.target = {right}\n"
        );
    }
    s += "end\n\n";
    s += &format!(
        "# a fresh reading after the last action: run the network, start its action\n\
         onevent prox\n\
         if fm_paused == 0 and fm_busy == 0 then\n{read}  callsub fm_network\n  callsub fm_start\n{monitor}end\n\n\
         # odometry at 100 Hz: each wheel travels |speed| target units for 10 ms; a wheel that\n\
         # cannot turn (the robot pushing a wall) ends the action after FM_TIMEOUT_TICKS\n\
         onevent motor\n\
         if fm_busy == 1 then\n\
         \x20 fm_sub = fm_sub + abs(motor.left.speed) + abs(motor.right.speed)\n\
         \x20 fm_todo = fm_todo - (fm_sub >> 5)\n\
         \x20 fm_sub = fm_sub & 31\n\
         \x20 fm_ticks = fm_ticks + 1\n\
         \x20 if fm_todo <= 0 or fm_ticks > FM_TIMEOUT_TICKS then\n\
         \x20   motor.left.target = 0\n    motor.right.target = 0\n    fm_busy = 0\n\
         \x20 end\nend\n"
    );
    s
}

/// The program of `c` reading `src`.
pub(crate) fn generate(c: &ExportedController, src: Source) -> AeslProgram {
    let r_max = c.robot().reading_max.round().clamp(1.0, 32767.0) as i64;
    let (n, h, units) = quantised(c, r_max);
    let read_len = n.min(src.len);
    let read = format!(
        "  call math.copy(fm_raw[0:{}], {}[0:{}])\n",
        read_len - 1,
        src.var,
        read_len - 1
    );
    let mut code = format!(
        "# fuzzymotiv controller {n}-{h}-2 for the Thymio II, exported by {}.\n\
         # Fixed point: readings as they are, activations and motor outputs in Q12 (4096 = 1.0);\n\
         # see README.txt.\n\n",
        crate::provenance()
    );
    code += &declarations(n, h, &units, c.motion);
    code += &format!(
        "\ncall math.fill(fm_rlo, 0)\ncall math.fill(fm_rmax, {r_max})\ncall math.fill(fm_raw, 0)\n\
         call math.fill(fm_x, 0)\nfm_x[0] = {r_max}\ncall math.fill(fm_h, 0)\nfm_h[0] = {ONE}\n\
         motor.left.target = 0\nmotor.right.target = 0\n"
    );
    match c.motion {
        Motion::Wheels => code += "timer.period[0] = FM_PERIOD_MS\n",
        Motion::Actions => code += "call math.muldiv(fm_vt, FM_V_MAX_DMM, 100, FM_UM_PER_UNIT)\n",
    }
    code += "\n";
    code += &sigma_sub();
    code += "\n";
    code += &network_sub(n, h);
    code += "\n";
    match c.motion {
        Motion::Wheels => {
            code += &format!(
                "# every control period: read the sensors, run the network, set the wheels\n\
                 onevent timer0\nif fm_paused == 0 then\n{read}  callsub fm_network\n  \
                 motor.left.target = fm_tgt[0]\n  motor.right.target = fm_tgt[1]\n{}end\n",
                monitor(n)
            );
        }
        Motion::Actions => code += &actions_code(&read, &monitor(n)),
    }
    let busy = if c.motion == Motion::Actions {
        "fm_busy = 0\n"
    } else {
        ""
    };
    code += &format!(
        "\n# check: stop, run the network once on the N readings given as the event's arguments\n\
         # (results in fm_m, fm_tgt, fm_act); fm_run resumes\n\
         onevent fm_test\nfm_paused = 1\n{busy}motor.left.target = 0\nmotor.right.target = 0\n\
         call math.copy(fm_raw, event.args[0:{}])\ncallsub fm_network\n\n\
         onevent fm_run\nfm_paused = 0\n",
        n - 1
    );
    AeslProgram {
        code,
        constants: constants(c),
        events: vec![
            ("fm_test".into(), n),
            ("fm_run".into(), 0),
            ("fm_state".into(), n + 2),
        ],
        n,
        h,
        units,
    }
}

/// The named constants: the speed of a target unit, v_max, the action tolerance, the control
/// period and the actions' wheel travels.
fn constants(c: &ExportedController) -> Vec<(String, i64)> {
    let r = c.robot();
    let dmm = |mm: f64| (mm * 10.0).round().clamp(0.0, 32767.0) as i64;
    let half_base = r.wheel_base / 2.0;
    let tol = (c.tolerance * f64::from(ONE))
        .floor()
        .clamp(-32768.0, 32767.0) as i64;
    vec![
        ("FM_UM_PER_UNIT".into(), UM_PER_UNIT),
        ("FM_V_MAX_DMM".into(), dmm(r.v_max)),
        ("FM_TOLERANCE".into(), tol),
        (
            "FM_PERIOD_MS".into(),
            (r.dt * 1000.0).round().clamp(1.0, 32767.0) as i64,
        ),
        ("FM_STRAIGHT_DMM".into(), dmm(r.straight_step())),
        (
            "FM_TURN_DMM".into(),
            dmm(half_base * r.turn_deg.to_radians()),
        ),
        (
            "FM_TURN180_DMM".into(),
            dmm(half_base * std::f64::consts::PI),
        ),
        ("FM_TIMEOUT_TICKS".into(), timeout_ticks(r)),
    ]
}

/// 10 ms ticks after which an action ends even if the odometer has not counted its travel:
/// three times the longest action (straight or turn180) at `v_max`, and at least 0.1 s.
fn timeout_ticks(r: &crate::export::KitRobot) -> i64 {
    let longest = r
        .straight_step()
        .max(r.wheel_base / 2.0 * std::f64::consts::PI);
    let ticks = 3.0 * longest / r.v_max.max(1e-3) / 0.01;
    if ticks.is_finite() {
        ticks.ceil().clamp(10.0, 32767.0) as i64
    } else {
        32767
    }
}

/// `text` as XML character data.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

impl AeslProgram {
    /// The .aesl document (Aseba Studio's and asebahttp's format) with the node `thymio-II`.
    pub(crate) fn aesl(&self) -> String {
        let mut s =
            String::from("<!DOCTYPE aesl-source>\n<network>\n\n<!--list of global events-->\n");
        for (name, size) in &self.events {
            s += &format!("<event size=\"{size}\" name=\"{name}\"/>\n");
        }
        s += "\n<!--list of constants-->\n";
        for (name, value) in &self.constants {
            s += &format!("<constant value=\"{value}\" name=\"{name}\"/>\n");
        }
        s += "\n<!--show keywords state-->\n<keywords flag=\"true\"/>\n\n<!--node thymio-II-->\n";
        s += &format!(
            "<node nodeId=\"1\" name=\"thymio-II\">{}</node>\n\n</network>\n",
            escape(&self.code)
        );
        s
    }
}
