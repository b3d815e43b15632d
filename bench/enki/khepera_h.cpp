// khepera_h: the fuzzymotiv `bench` workload, re-expressed in the Enki 2D robot simulator.
//
// One Khepera in the H room, driven by an 8-6-2 logistic MLP with fixed random weights, for
// whole 400-step trials (dt = 0.1 s) until N robot-steps are done; repeated R times; the median
// wall-clock time is reported as JSON, like `fuzzymotiv bench --json`.
//
// Units: Enki's Khepera model is in centimetres (radius 2.6, wheel distance 5.2, IR range 10,
// wheel speeds in cm/s), so 1 Enki unit = 1 cm = 10 mm of fuzzymotiv. See ../README.md.
//
// Usage: khepera_h [--steps N] [--repeat R] [--seed S] [--probe] [--bench FILE] [--trace] [--stock-ir]
//                  [--one-object] [--stats]
//   --probe  print the Khepera's IR sensor geometry and response curve, then exit
//   --bench FILE  write Enki's Khepera measured as on a bench, in `fuzzymotiv calibrate`'s input
//            format (sensor,distance_mm,reading), then exit: the front sensor head-on to a wall
//            from contact (11.5 mm) out to 110 mm, five readings per distance, each reading
//            mapped as `fuzzymotiv transfer` maps it onto the network's scale: min(raw ×
//            1023/1200, 1023), rounded (issue 54 item 4: Enki as the calibration bench)
//   --trace  print one trial's trajectory (x y heading in mm/deg) to stdout, then exit
//   --stats  run one trial per genome (200) and print how close to walls the robots were
//   --one-object  express the H's notches as one two-part static object instead of two blocks
//   --stock-ir  do not work around libenki 1.6.99's stale IR ray values (see IRValues below)

#include <enki/PhysicalEngine.h>
#include <enki/robots/khepera/Khepera.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

// ---- fuzzymotiv's parameters, converted to Enki's centimetres --------------------------------
constexpr double MM = 0.1;                  // cm per mm
constexpr double ROOM_W = 900 * MM;         // world width
constexpr double ROOM_H = 800 * MM;         // world height
constexpr double HOME_X = 100 * MM;
constexpr double HOME_Y = 150 * MM;
constexpr double HOME_HEADING = M_PI / 2;   // 90°
constexpr double RADIUS = 27.5 * MM;        // Enki's default is 2.6 cm
constexpr double WHEEL_BASE = 53.0 * MM;    // Enki's default is 5.2 cm
constexpr double V_MAX = 80.0 * MM;         // 8 cm/s
constexpr double DT = 0.1;
constexpr int TRIAL_STEPS = 400;
constexpr double NOISE = 0.06;              // U(0.94, 1.06) on sensors and wheels
constexpr int HIDDEN = 6;
constexpr int INPUTS = 8;
constexpr int GENOME = HIDDEN * (INPUTS + 1) + 2 * (HIDDEN + 1);  // 68
constexpr int GENOMES = 200;                // like fuzzymotiv's population of 200
constexpr double WALL_HEIGHT = 10.0;        // above the IR sensors' 1.8 cm

// ---- xoshiro256++ (the generator fuzzymotiv uses), seeded by splitmix64 --------------------
struct Xoshiro {
    uint64_t s[4];
    explicit Xoshiro(uint64_t seed) {
        for (auto& w : s) {
            seed += 0x9e3779b97f4a7c15ULL;
            uint64_t z = seed;
            z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
            z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
            w = z ^ (z >> 31);
        }
    }
    static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    uint64_t next() {
        const uint64_t r = rotl(s[0] + s[3], 23) + s[0];
        const uint64_t t = s[1] << 17;
        s[2] ^= s[0];
        s[3] ^= s[1];
        s[1] ^= s[2];
        s[0] ^= s[3];
        s[2] ^= t;
        s[3] = rotl(s[3], 45);
        return r;
    }
    double uniform01() { return (next() >> 11) * (1.0 / 9007199254740992.0); }
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }
};

inline double logistic(double x) { return 1.0 / (1.0 + std::exp(-x)); }

// 8-6-2 MLP, genome laid out like fuzzymotiv's: per hidden unit [bias, 8 weights], then per
// output [bias, 6 weights].
void mlp(const double* w, const double in[INPUTS], double out[2]) {
    double h[HIDDEN];
    for (int j = 0; j < HIDDEN; ++j, w += INPUTS + 1) {
        double s = w[0];
        for (int k = 0; k < INPUTS; ++k) s += w[k + 1] * in[k];
        h[j] = logistic(s);
    }
    for (int o = 0; o < 2; ++o, w += HIDDEN + 1) {
        double s = w[0];
        for (int j = 0; j < HIDDEN; ++j) s += w[j + 1] * h[j];
        out[o] = logistic(s);
    }
}

// Debian's libenki 1.6.99 has a bug: IRSensor::init() refills the per-ray distances with the
// range but leaves the per-ray *values* from the previous step, so after a wall has been seen at
// distance d a sensor keeps reporting F(d) until something closer appears (checked by
// disassembling /usr/lib/libenki.so.2: init() fills one vector only; upstream's init() also
// zeroes rayValues). This accessor lets the harness zero them before each World::step (8 x 3
// doubles, negligible cost). `--stock-ir` turns the fix off.
struct IRValues : Enki::IRSensor {
    static void clear(Enki::IRSensor* s) {
        std::vector<double>& v = s->*(&IRValues::rayValues);  // protected member via derived
        std::fill(v.begin(), v.end(), 0.0);
    }
};
bool g_fix_ir = true;

// The stock Enki Khepera, with fuzzymotiv's body radius and wheel base, and Enki's own ±5 % motor
// noise switched off (this harness applies fuzzymotiv's 6 % noise itself).
struct BenchKhepera : public Enki::Khepera {
    BenchKhepera() : Enki::Khepera(CAPABILITIY_BASIC_SENSORS) {
        distBetweenWheels = WHEEL_BASE;
        noiseAmount = 0.0;
        setCylindric(RADIUS, 5, 80);
    }
    // Enki turns leftSpeed/rightSpeed into the body's velocity command in controlStep(), which
    // World::step calls *after* its physics, so a command would only move the robot one step
    // later. Latching it now gives fuzzymotiv's order: sense, decide, move (no noise is drawn:
    // noiseAmount is 0).
    void latch_command() { DifferentialWheeled::controlStep(0.0); }
    void clear_ir() {
        if (!g_fix_ir) return;
        for (int i = 0; i < 8; ++i) IRValues::clear(ir(i));
    }
    Enki::IRSensor* ir(int i) {
        Enki::IRSensor* s[8] = {&infraredSensor0, &infraredSensor1, &infraredSensor2,
                                &infraredSensor3, &infraredSensor4, &infraredSensor5,
                                &infraredSensor6, &infraredSensor7};
        return s[i];
    }
};

// The H room: a 90 x 80 cm square-walled world (Enki's own walls are the outer edges) plus two
// static (negative-mass) rectangles for the notches x in [20, 70] x y in [0, 30] and
// x in [20, 70] x y in [50, 80]. Enki also tests the two blocks against each other every step
// (their bounding circles overlap), but that is cheaper than the alternative below.
Enki::PhysicalObject* make_block(double x0, double y0, double x1, double y1) {
    auto* o = new Enki::PhysicalObject();
    o->setRectangular(x1 - x0, y1 - y0, WALL_HEIGHT, -1);  // negative mass: immovable
    o->pos = Enki::Point((x0 + x1) / 2, (y0 + y1) / 2);
    o->angle = 0;
    return o;
}

// Alternative (--one-object): one static object made of two convex parts. No block-block test,
// but its bounding circle (r = 47 cm) covers the whole room, so every IR ray is tested against
// both parts every step: ~1.7x more instructions per robot-step than the two-block form.
Enki::PhysicalObject* make_h_walls() {
    auto* o = new Enki::PhysicalObject();
    const double cx = 450 * MM, cy = 400 * MM;  // object origin = centre of the two notches
    auto rect = [&](double x0, double y0, double x1, double y1) {
        Enki::Polygon p;  // counter-clockwise, relative to (cx, cy)
        p << Enki::Point(x0 - cx, y0 - cy) << Enki::Point(x1 - cx, y0 - cy)
          << Enki::Point(x1 - cx, y1 - cy) << Enki::Point(x0 - cx, y1 - cy);
        return Enki::PhysicalObject::Part(p, WALL_HEIGHT);
    };
    Enki::PhysicalObject::Hull hull;
    hull.push_back(rect(200 * MM, 0, 700 * MM, 300 * MM));
    hull.push_back(rect(200 * MM, 500 * MM, 700 * MM, 800 * MM));
    o->setCustomHull(hull, -1);
    o->pos = Enki::Point(cx, cy);  // parts are symmetric about the origin: centroid stays put
    o->angle = 0;
    return o;
}

bool g_one_object = false;

// Distance (mm) from (x, y) to the nearest edge of the H polygon (diagnostics only, untimed).
double clearance_mm(double x, double y) {
    static const double P[12][2] = {{0, 0},     {200, 0},   {200, 300}, {700, 300},
                                    {700, 0},   {900, 0},   {900, 800}, {700, 800},
                                    {700, 500}, {200, 500}, {200, 800}, {0, 800}};
    double best = INFINITY;
    for (int i = 0; i < 12; ++i) {
        const double ax = P[i][0], ay = P[i][1], bx = P[(i + 1) % 12][0], by = P[(i + 1) % 12][1];
        const double dx = bx - ax, dy = by - ay;
        const double u = std::clamp(((x - ax) * dx + (y - ay) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
        best = std::min(best, std::hypot(x - ax - u * dx, y - ay - u * dy));
    }
    return best;
}

struct Sim {
    Enki::World world{ROOM_W, ROOM_H};
    BenchKhepera* robot = new BenchKhepera();
    double sensor_max = 0;  // response of a sensor touching a wall, for normalising to [0, 1]

    Sim() {
        if (g_one_object) {
            world.addObject(make_h_walls());
        } else {
            world.addObject(make_block(200 * MM, 0, 700 * MM, 300 * MM));
            world.addObject(make_block(200 * MM, 500 * MM, 700 * MM, 800 * MM));
        }
        world.addObject(robot);
    }

    void place(double x, double y, double heading) {
        robot->pos = Enki::Point(x, y);
        robot->angle = heading;
        robot->speed = Enki::Vector(0, 0);
        robot->angSpeed = 0;
        robot->leftSpeed = robot->rightSpeed = 0;
        robot->latch_command();  // drop the previous trial's last command
        robot->resetEncoders();
        // Enki computes sensor values at the end of World::step; a zero-speed step refreshes
        // them for the new pose (physics moves nothing at zero speed).
        robot->clear_ir();
        world.step(DT);
    }

    // One whole trial from the home pose. With `trace`, prints each step's pose (mm, degrees)
    // and the body's clearance to the nearest H wall (mm; negative = penetration).
    void trial(const double* genome, Xoshiro& rng, FILE* trace) {
        place(HOME_X, HOME_Y, HOME_HEADING);
        for (int t = 0; t < TRIAL_STEPS; ++t) {
            double in[INPUTS];
            for (int k = 0; k < INPUTS; ++k) {
                double v = robot->ir(k)->getValue() * rng.uniform(1 - NOISE, 1 + NOISE);
                in[k] = std::clamp(v, 0.0, sensor_max) / sensor_max;
            }
            double m[2];
            mlp(genome, in, m);
            robot->leftSpeed = (2 * m[0] - 1) * V_MAX * rng.uniform(1 - NOISE, 1 + NOISE);
            robot->rightSpeed = (2 * m[1] - 1) * V_MAX * rng.uniform(1 - NOISE, 1 + NOISE);
            robot->latch_command();
            robot->clear_ir();
            world.step(DT);
            if (trace)
                std::fprintf(trace, "%d %.3f %.3f %.2f %.3f\n", t, robot->pos.x / MM,
                             robot->pos.y / MM, robot->angle * 180 / M_PI,
                             clearance_mm(robot->pos.x / MM, robot->pos.y / MM) - RADIUS / MM);
        }
    }
};

double now() {
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
}

/// The front sensor (2) at `d_mm` from the left outer wall along its axis, heading −x.
double front_reading(Sim& sim, double d_mm) {
    sim.place(100 * MM, 400 * MM, M_PI);
    const double off = sim.robot->pos.x - sim.robot->ir(2)->getAbsolutePosition().x;
    sim.place(d_mm * MM + off, 400 * MM, M_PI);
    return sim.robot->ir(2)->getValue();
}

/// `--bench FILE`: Enki's Khepera as a bench measurement for `fuzzymotiv calibrate`, readings
/// on the network's scale as `fuzzymotiv transfer` maps them (min(raw × 1023/1200, 1023)).
int write_bench(Sim& sim, const char* path) {
    FILE* f = std::fopen(path, "w");
    if (!f) {
        std::fprintf(stderr, "khepera_h: --bench %s: cannot write it\n", path);
        return 2;
    }
    std::fprintf(f,
                 "# Enki's Khepera measured as on a bench (make -C bench/enki && target/bench/khepera_h\n"
                 "# --bench FILE): its front sensor head-on to a wall, 5 readings per distance (mm\n"
                 "# from the sensor along its axis), Enki's noise included, each reading mapped as\n"
                 "# `fuzzymotiv transfer` maps Enki's Khepera onto the network: min(raw * 1023/1200,\n"
                 "# 1023), rounded. Not a real robot: Enki as the calibration bench (issue 54).\n"
                 "sensor,distance_mm,reading\n");
    std::vector<double> distances = {11.5};
    for (int d = 15; d <= 110; d += 5) distances.push_back(d);
    for (double d : distances) {
        for (int k = 0; k < 5; ++k) {
            const double v = std::min(front_reading(sim, d) * 1023.0 / 1200.0, 1023.0);
            std::fprintf(f, "0,%g,%ld\n", d, std::lround(v));
        }
    }
    return std::fclose(f) == 0 ? 0 : 2;
}

void usage() {
    std::fprintf(stderr, "usage: khepera_h [--steps N] [--repeat R] [--seed S] [--probe] [--bench FILE]\n"
                         "                 [--trace]\n"
                         "                 [--stats]\n"
                         "                 [--stock-ir] [--one-object]\n");
    std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
    long steps = 2000000;
    int repeat = 5;
    uint64_t seed = 1;
    bool probe = false, trace = false, stats = false;
    const char* bench = nullptr;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        auto val = [&]() -> const char* {
            if (i + 1 >= argc) usage();
            return argv[++i];
        };
        if (a == "--steps") steps = std::atol(val());
        else if (a == "--repeat") repeat = std::atoi(val());
        else if (a == "--seed") seed = std::strtoull(val(), nullptr, 10);
        else if (a == "--probe") probe = true;
        else if (a == "--bench") bench = val();
        else if (a == "--trace") trace = true;
        else if (a == "--stats") stats = true;
        else if (a == "--stock-ir") g_fix_ir = false;
        else if (a == "--one-object") g_one_object = true;
        else usage();
    }
    if (steps < 1 || repeat < 1) usage();

    Enki::random.setSeed(seed);  // Enki's own generator (IR sensor Gaussian noise)
    Sim sim;

    // Calibrate the normalisation: sensor 2 (front) facing the left outer wall at contact.
    {
        double sum = 0;
        const int n = 200;
        for (int k = 0; k < n; ++k) {
            sim.place(RADIUS + 0.01, 400 * MM, M_PI);
            sum += std::max(sim.robot->ir(2)->getValue(), sim.robot->ir(3)->getValue());
        }
        sim.sensor_max = sum / n;
    }

    if (bench) return write_bench(sim, bench);
    if (probe) {
        std::printf("sensor  rays  aperture_deg  range_cm  abs_pos_cm(at home)  abs_orient_deg\n");
        sim.place(HOME_X, HOME_Y, HOME_HEADING);
        for (int k = 0; k < 8; ++k) {
            auto* s = sim.robot->ir(k);
            std::printf("%d       %u     %.1f          %.1f      (%.2f, %.2f)        %.1f\n", k,
                        s->getRayCount(), s->getAperture() * 180 / M_PI, s->getRange(),
                        s->getAbsolutePosition().x, s->getAbsolutePosition().y,
                        s->getAbsoluteOrientation() * 180 / M_PI);
        }
        std::printf("sensor_max (front sensor at wall contact, mean of 200) = %.1f\n", sim.sensor_max);
        std::printf("\nfront sensor facing a wall: distance sensor->wall (mm), mean value of 200\n");
        // Robot faces -x (heading 180°) towards the left outer wall at x = 0; distances below
        // ~11.5 mm cannot be reached (the sensor sits inside the 27.5 mm body) and read as contact.
        for (double d_mm : {11.5, 15.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0,
                            90.0, 100.0, 120.0}) {
            double sum = 0;
            double sx = 0;
            for (int k = 0; k < 200; ++k) {
                // place so that sensor 2's x is d_mm from the wall
                sim.place(100 * MM, 400 * MM, M_PI);
                const double off = sim.robot->pos.x - sim.robot->ir(2)->getAbsolutePosition().x;
                sim.place(d_mm * MM + off, 400 * MM, M_PI);
                sx = sim.robot->ir(2)->getAbsolutePosition().x;
                sum += sim.robot->ir(2)->getValue();
            }
            std::printf("  d=%6.1f mm (sensor x=%.2f cm)  value=%7.1f\n", d_mm, sx, sum / 200);
        }
        return 0;
    }

    Xoshiro rng(seed);
    std::vector<double> genomes(GENOMES * GENOME);
    for (auto& g : genomes) g = rng.uniform(-1, 1);

    if (stats) {
        // Untimed: where the benchmark's robots spend their steps (cost depends on it).
        FILE* tmp = std::tmpfile();
        for (int g = 0; g < GENOMES; ++g) sim.trial(&genomes[g * GENOME], rng, tmp);
        std::rewind(tmp);
        long n = 0, contact = 0, near = 0;
        double sum = 0, t, x, y, h, c;
        while (std::fscanf(tmp, "%lf %lf %lf %lf %lf", &t, &x, &y, &h, &c) == 5) {
            ++n;
            sum += c;
            contact += c < 1.0;
            near += c < 100.0;  // within Enki's 10 cm IR range of a wall (roughly)
        }
        std::printf("{\"trials\": %d, \"steps\": %ld, \"mean_clearance_mm\": %.1f, "
                    "\"contact_fraction\": %.3f, \"within_100mm_fraction\": %.3f}\n",
                    GENOMES, n, sum / n, double(contact) / n, double(near) / n);
        return 0;
    }
    if (trace) {
        std::printf("# step x_mm y_mm heading_deg clearance_mm\n");
        sim.trial(&genomes[0], rng, stdout);
        return 0;
    }

    const long trials = (steps + TRIAL_STEPS - 1) / TRIAL_STEPS;
    std::vector<double> secs;
    double sink = 0;
    for (int r = 0; r < repeat; ++r) {
        const double t0 = now();
        for (long k = 0; k < trials; ++k) {
            sim.trial(&genomes[(k % GENOMES) * GENOME], rng, nullptr);
            sink += sim.robot->pos.x;
        }
        secs.push_back(now() - t0);
    }
    std::vector<double> sorted = secs;
    std::sort(sorted.begin(), sorted.end());
    const double median = sorted[sorted.size() / 2];
    const long robot_steps = trials * TRIAL_STEPS;
    std::printf("{\n  \"simulator\": \"enki\",\n  \"room\": \"H\",\n  \"robot_steps\": %ld,\n"
                "  \"seconds\": %.6f,\n  \"robot_steps_per_sec\": %.1f,\n  \"repeat\": %d,\n"
                "  \"statistic\": \"median\",\n  \"all_seconds\": [",
                robot_steps, median, robot_steps / median, repeat);
    for (size_t i = 0; i < secs.size(); ++i) std::printf("%s%.6f", i ? ", " : "", secs[i]);
    std::printf("],\n  \"sensor_max\": %.1f,\n  \"world_steps_per_trial\": %d,\n"
                "  \"ir_stale_value_fix\": %s,\n  \"h_notches\": \"%s\"\n}\n",
                sim.sensor_max, TRIAL_STEPS + 1, g_fix_ir ? "true" : "false",
                g_one_object ? "one static object, two parts" : "two static objects");
    if (sink == 12345.678) std::fprintf(stderr, "%f\n", sink);
    return 0;
}
