// The Enki side of `fuzzymotiv transfer` (crates/fuzzymotiv-pipeline/src/pipeline/transfer.rs writes
// this file next to an exported controller, compiles it with `c++` against Debian's
// libenki-dev and the exported fm_controller.c, and runs it once per test run).
//
// Usage: fm_enki SCENARIO > LOG
//
// SCENARIO is plain text, one `key values…` per line, every length in Enki's centimetres:
//   robot khepera|epuck2|thymio2   Enki's own model (Khepera, EPuck, Thymio2; stock bodies)
//   motion actions|wheels          how the controller's outputs move the robot
//   steps T                        control steps
//   dt S                           the control period (s); `actions` also the straight move's time
//   v_max V                        the robot's top wheel speed (cm/s)
//   scale K                        Enki reading -> network reading: min(K * raw, reading_max)
//   reading_max M                  the robot's reading scale (the exported C divides by it)
//   physics_dt H                   the longest physics step (s)
//   seed N                         Enki's random generator (its IR and wheel noise)
//   world W H                      Enki's walled rectangle (cm)
//   home X Y HEADING               the start pose (cm, rad)
//   block CX CY LENGTH WIDTH ANGLE an immovable wall (a rectangle; any number of them)
//
// Output: per control step one line
//   step T X Y ANGLE RAW_0..RAW_{N-1} IN_0..IN_{N-1} ML MR ACTION COLLIDED
// with the pose at the step's start (cm, rad), Enki's raw readings, the readings given to the
// network, its motor outputs, the action code the exported C returned (0 straight, 1 left30,
// 2 right30, 3 turn180) and whether the body touched a wall during the step (Enki's collision
// callback); then `end X Y ANGLE`, the final pose. Numbers are printed with 17 significant
// digits, so each reads back as the same double.
//
// Motion: `wheels` sets Enki's wheel speeds to (2m - 1) * v_max for one control period.
// `actions` executes the label: `straight` drives both wheels at v = min(v_max, Enki's own
// top speed) for the time the commanded speed takes to cover v_max * dt; `left30`/`right30`
// and `turn180` turn on the spot (wheels at -v and +v) for the time the commanded speeds take
// to turn the body by 30 or 180 degrees on Enki's axle (dead reckoning of the command, the
// stopping rule a robot's odometry applies); each action's time is split into equal physics
// steps of at most `physics_dt`, then the network runs again on the readings Enki computed at
// the end. Enki's own wheel noise and collisions move the body, so its pose can differ from
// the one the odometry assumes; the log records Enki's pose.

#include <enki/PhysicalEngine.h>
#include <enki/robots/e-puck/EPuck.h>
#include <enki/robots/khepera/Khepera.h>
#include <enki/robots/thymio2/Thymio2.h>

extern "C" {
#include "fm_controller.h"
}

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

[[noreturn]] void fail(const std::string& message) {
    std::fprintf(stderr, "fm_enki: %s\n", message.c_str());
    std::exit(3);
}

struct Scenario {
    std::string robot, motion;
    int steps = 0;
    double dt = 0, v_max = 0, scale = 1, reading_max = 1023, physics_dt = 0.01;
    unsigned long seed = 0;
    double world_w = 0, world_h = 0, home_x = 0, home_y = 0, home_heading = 0;
    struct Block {
        double cx, cy, length, width, angle;
    };
    std::vector<Block> blocks;
};

Scenario read_scenario(const char* path) {
    std::ifstream in(path);
    if (!in) fail(std::string("cannot read the scenario ") + path);
    Scenario s;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream l(line);
        std::string key;
        if (!(l >> key)) continue;
        bool ok = true;
        if (key == "robot") ok = bool(l >> s.robot);
        else if (key == "motion") ok = bool(l >> s.motion);
        else if (key == "steps") ok = bool(l >> s.steps);
        else if (key == "dt") ok = bool(l >> s.dt);
        else if (key == "v_max") ok = bool(l >> s.v_max);
        else if (key == "scale") ok = bool(l >> s.scale);
        else if (key == "reading_max") ok = bool(l >> s.reading_max);
        else if (key == "physics_dt") ok = bool(l >> s.physics_dt);
        else if (key == "seed") ok = bool(l >> s.seed);
        else if (key == "world") ok = bool(l >> s.world_w >> s.world_h);
        else if (key == "home") ok = bool(l >> s.home_x >> s.home_y >> s.home_heading);
        else if (key == "block") {
            Scenario::Block b{};
            ok = bool(l >> b.cx >> b.cy >> b.length >> b.width >> b.angle);
            s.blocks.push_back(b);
        } else fail("unknown scenario key " + key);
        if (!ok) fail("bad values for " + key);
    }
    if (s.steps <= 0 || s.dt <= 0 || s.v_max <= 0 || s.physics_dt <= 0) fail("incomplete scenario");
    return s;
}

// Debian's libenki 1.6.99 keeps an IR ray's last value when it stops hitting anything
// (bench/enki/README.md): the values are zeroed before every world step, as upstream does.
struct IRValues : Enki::IRSensor {
    static void clear(Enki::IRSensor* s) {
        std::vector<double>& v = s->*(&IRValues::rayValues);
        std::fill(v.begin(), v.end(), 0.0);
    }
};

// What the harness needs of a robot, over Enki's models.
struct Body {
    virtual ~Body() = default;
    virtual Enki::DifferentialWheeled* robot() = 0;
    virtual std::vector<Enki::IRSensor*> sensors() = 0;
    virtual double axle() const = 0;
    virtual double top_speed() const = 0;
    virtual long hits() const = 0;
    virtual void latch() = 0;
};

template <class R>
struct Tracked : R, Body {
    long collisions = 0;
    void collisionEvent(Enki::PhysicalObject*) override { ++collisions; }
    Enki::DifferentialWheeled* robot() override { return this; }
    double axle() const override { return this->distBetweenWheels; }
    double top_speed() const override { return this->maxSpeed; }
    long hits() const override { return collisions; }
    // Enki turns the wheel speeds into the body's motion in controlStep(), which World::step
    // runs after its physics: latching the command now moves the body in this step (sense,
    // decide, move, as fuzzymotiv's step); Enki's wheel noise is drawn here.
    void latch() override { Enki::DifferentialWheeled::controlStep(0.0); }
    std::vector<Enki::IRSensor*> sensors() override;
};

template <>
std::vector<Enki::IRSensor*> Tracked<Enki::Khepera>::sensors() {
    return {&infraredSensor0, &infraredSensor1, &infraredSensor2, &infraredSensor3,
            &infraredSensor4, &infraredSensor5, &infraredSensor6, &infraredSensor7};
}
template <>
std::vector<Enki::IRSensor*> Tracked<Enki::EPuck>::sensors() {
    return {&infraredSensor0, &infraredSensor1, &infraredSensor2, &infraredSensor3,
            &infraredSensor4, &infraredSensor5, &infraredSensor6, &infraredSensor7};
}
template <>
std::vector<Enki::IRSensor*> Tracked<Enki::Thymio2>::sensors() {
    return {&infraredSensor0, &infraredSensor1, &infraredSensor2, &infraredSensor3,
            &infraredSensor4, &infraredSensor5, &infraredSensor6};
}

struct Sim {
    const Scenario& s;
    Enki::World world;
    Body* body = nullptr;
    Enki::DifferentialWheeled* robot = nullptr;

    explicit Sim(const Scenario& sc) : s(sc), world(sc.world_w, sc.world_h) {
        for (const auto& b : s.blocks) {
            auto* o = new Enki::PhysicalObject();
            o->setRectangular(b.length, b.width, 10.0, -1);  // negative mass: immovable
            o->pos = Enki::Point(b.cx, b.cy);
            o->angle = b.angle;
            world.addObject(o);
        }
        if (s.robot == "khepera") body = new Tracked<Enki::Khepera>();
        else if (s.robot == "epuck2") body = new Tracked<Enki::EPuck>();
        else if (s.robot == "thymio2") body = new Tracked<Enki::Thymio2>();
        else fail("no Enki model for robot " + s.robot);
        robot = body->robot();
        world.addObject(robot);
        if (int(body->sensors().size()) != FM_INPUTS) {
            fail("the exported controller has " + std::to_string(FM_INPUTS) +
                 " inputs, Enki's " + s.robot + " " + std::to_string(body->sensors().size()) +
                 " IR sensors");
        }
    }

    // Runs the world for `time` seconds at wheel speeds (l, r) cm/s in equal physics steps of
    // at most physics_dt; returns whether the body touched a wall meanwhile.
    bool drive(double l, double r, double time) {
        const long before = body->hits();
        robot->leftSpeed = l;
        robot->rightSpeed = r;
        body->latch();
        const int n = std::max(1, int(std::ceil(time / s.physics_dt - 1e-9)));
        for (int k = 0; k < n; ++k) {
            for (auto* ir : body->sensors()) IRValues::clear(ir);
            world.step(time / n);
        }
        return body->hits() > before;
    }

    void place_home() {
        robot->pos = Enki::Point(s.home_x, s.home_y);
        robot->angle = s.home_heading;
        robot->speed = Enki::Vector(0, 0);
        robot->angSpeed = 0;
        robot->resetEncoders();
        drive(0, 0, s.dt);  // computes the readings at home; nothing moves
    }

    // Executes one action label (see the file's comment); returns whether it collided.
    bool act(int action) {
        const double v = std::min(s.v_max, body->top_speed());
        const double spin = 2 * v / body->axle();  // rad/s with wheels at -v and +v
        switch (action) {
        case FM_ACTION_STRAIGHT: return drive(v, v, s.v_max * s.dt / v);
        case FM_ACTION_LEFT30: return drive(-v, v, (M_PI / 6) / spin);
        case FM_ACTION_RIGHT30: return drive(v, -v, (M_PI / 6) / spin);
        default: return drive(-v, v, M_PI / spin);
        }
    }

    void run() {
        place_home();
        const int n = FM_INPUTS;
        std::vector<double> raw(n), in(n);
        for (int t = 0; t < s.steps; ++t) {
            auto sensors = body->sensors();
            for (int k = 0; k < n; ++k) {
                raw[k] = sensors[k]->getValue();
                in[k] = std::min(raw[k] * s.scale, s.reading_max);
            }
            double motors[2];
            int action = 0;
            fm_controller_step_readings(in.data(), motors, &action);
            std::printf("step %d %.17g %.17g %.17g", t, robot->pos.x, robot->pos.y, robot->angle);
            for (double v : raw) std::printf(" %.17g", v);
            for (double v : in) std::printf(" %.17g", v);
            bool hit;
            if (s.motion == "wheels") {
                hit = drive((2 * motors[0] - 1) * s.v_max, (2 * motors[1] - 1) * s.v_max, s.dt);
            } else {
                hit = act(action);
            }
            std::printf(" %.17g %.17g %d %d\n", motors[0], motors[1], action, hit ? 1 : 0);
        }
        std::printf("end %.17g %.17g %.17g\n", robot->pos.x, robot->pos.y, robot->angle);
    }
};

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) fail("usage: fm_enki SCENARIO");
    const Scenario s = read_scenario(argv[1]);
    Enki::random.setSeed(s.seed);
    Sim sim(s);
    sim.run();
    return 0;
}
