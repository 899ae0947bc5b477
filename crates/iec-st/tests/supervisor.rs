//! A hand-written supervisor in the style the exporter produces: a constant
//! 2-D transition array, a state variable, edge detection, an uncontrollable
//! then a controllable phase, a fault mode, wired to located I/O by a
//! PROGRAM. Checked scan by scan against a scenario and against a Rust model
//! of the same logic over 10,000 pseudo-random scans.

use iec_st::{parse, Instance, Slot, Value};

const SOURCE: &str = "
(* Events: 0 start (controllable), 1 finish (uncontrollable), 2 reset (controllable). *)
FUNCTION_BLOCK supervisor
VAR_INPUT finish_sensor, req_start, req_reset, ack : BOOL; END_VAR
VAR_OUTPUT motor, fault : BOOL; S_x : SINT; fired : UDINT; END_VAR
VAR CONSTANT
    EV_START : INT := 0; EV_FINISH : INT := 1; EV_RESET : INT := 2;
    // TR[state, event]: the next state, -1 where the event is disabled.
    TR : ARRAY [0..2, 0..2] OF SINT := [1, -1, -1,   -1, 2, -1,   2(-1), 0];
    MAX_CYCLES : UDINT := 3;
END_VAR
VAR last_sensor : BOOL; next : SINT; cycles : UDINT; END_VAR

IF fault THEN
    motor := FALSE;
    IF ack THEN fault := FALSE; S_x := 0; END_IF;
    RETURN;
END_IF;

(* Uncontrollable phase: the sensor's rising edge. *)
IF finish_sensor AND NOT last_sensor THEN
    next := TR[S_x, EV_FINISH];
    IF next < 0 THEN
        fault := TRUE; motor := FALSE; last_sensor := finish_sensor;
        RETURN;
    END_IF;
    S_x := next; fired := fired + 1;
END_IF;
last_sensor := finish_sensor;

(* Controllable phase: the first enabled request wins. *)
IF req_start AND TR[S_x, EV_START] >= 0 AND cycles < MAX_CYCLES THEN
    S_x := TR[S_x, EV_START]; fired := fired + 1; cycles := cycles + 1;
ELSIF req_reset AND TR[S_x, EV_RESET] >= 0 THEN
    S_x := TR[S_x, EV_RESET]; fired := fired + 1;
END_IF;
motor := S_x = 1;
END_FUNCTION_BLOCK

PROGRAM main
VAR
    sensor AT %IX0.0 : BOOL; start AT %IX0.1 : BOOL; reset AT %IX0.2 : BOOL; ack AT %IX0.3 : BOOL;
    motor AT %QX0.0 : BOOL; alarm AT %QX0.1 : BOOL; state AT %QB1 : SINT;
    sc : supervisor;
END_VAR
sc(finish_sensor := sensor, req_start := start, req_reset := reset, ack := ack,
   motor => motor, fault => alarm, S_x => state);
END_PROGRAM
";

struct Io {
    inputs: [Slot; 4],
    motor: Slot,
    alarm: Slot,
    state: Slot,
    fired: Slot,
}

fn setup() -> (Instance, Io) {
    let file = parse(SOURCE).unwrap();
    let p = file.instantiate("main").unwrap();
    let io = Io {
        inputs: ["%IX0.0", "%IX0.1", "%ix0.2", "%IX0.3"].map(|a| p.slot_at(a).unwrap()),
        motor: p.slot_at("%QX0.0").unwrap(),
        alarm: p.slot("alarm").unwrap(),
        state: p.slot("state").unwrap(),
        fired: p.slot("sc.fired").unwrap(),
    };
    (p, io)
}

/// One scan: inputs in, call, (motor, alarm, state, fired) out.
fn scan(p: &mut Instance, io: &Io, inputs: [bool; 4]) -> (bool, bool, i64, i64) {
    for (slot, v) in io.inputs.iter().zip(inputs) {
        p.set_slot(*slot, Value::Bool(v)).unwrap();
    }
    p.call().unwrap();
    let b = |s: Slot| p.get_slot(s).unwrap().as_bool().unwrap();
    let i = |s: Slot| p.get_slot(s).unwrap().as_i64().unwrap();
    (b(io.motor), b(io.alarm), i(io.state), i(io.fired))
}

#[test]
fn a_scenario_scan_by_scan() {
    let (mut p, io) = setup();
    let t = true;
    let f = false;
    // (sensor, start, reset, ack) -> (motor, alarm, state, fired)
    let scenario = [
        ([f, t, f, f], (t, f, 1, 1)), // start: IDLE -> RUN
        ([f, t, f, f], (t, f, 1, 1)), // start disabled in RUN
        ([t, f, f, f], (f, f, 2, 2)), // finish edge: RUN -> DONE
        ([t, f, t, f], (f, f, 0, 3)), // no edge; reset: DONE -> IDLE
        ([f, t, f, f], (t, f, 1, 4)), // second cycle
        ([t, f, f, f], (f, f, 2, 5)),
        ([f, f, t, f], (f, f, 0, 6)),
        ([f, t, f, f], (t, f, 1, 7)), // third cycle
        ([f, f, f, f], (t, f, 1, 7)),
        ([t, f, t, f], (f, f, 0, 9)), // finish then reset in one scan
        ([f, t, f, f], (f, f, 0, 9)), // cycle limit reached: start refused
        ([t, f, f, f], (f, t, 0, 9)), // finish undefined in IDLE: fault
        ([f, t, f, f], (f, t, 0, 9)), // fault holds without ack
        ([f, f, f, t], (f, f, 0, 9)), // ack clears it
    ];
    for (k, (inputs, expected)) in scenario.into_iter().enumerate() {
        assert_eq!(scan(&mut p, &io, inputs), expected, "scan {k}");
    }
    assert_eq!(p.get("sc.cycles").unwrap().as_i64(), Some(3));
    assert_eq!(p.get("sc.TR[2, 2]").unwrap().as_i64(), Some(0));
    assert_eq!(p.get("sc.TR[1,1]").unwrap().as_i64(), Some(2));
}

/// The same supervisor in Rust, to run in lockstep.
#[derive(Default)]
struct Model {
    state: i64,
    fired: i64,
    cycles: i64,
    fault: bool,
    motor: bool,
    last_sensor: bool,
}

impl Model {
    const TR: [[i64; 3]; 3] = [[1, -1, -1], [-1, 2, -1], [-1, -1, 0]];

    fn scan(&mut self, [sensor, start, reset, ack]: [bool; 4]) -> (bool, bool, i64, i64) {
        self.step(sensor, start, reset, ack);
        (self.motor, self.fault, self.state, self.fired)
    }

    fn step(&mut self, sensor: bool, start: bool, reset: bool, ack: bool) {
        if self.fault {
            self.motor = false;
            if ack {
                self.fault = false;
                self.state = 0;
            }
            return;
        }
        if sensor && !self.last_sensor {
            let next = Self::TR[self.state as usize][1];
            if next < 0 {
                self.fault = true;
                self.motor = false;
                self.last_sensor = sensor;
                return;
            }
            self.state = next;
            self.fired += 1;
        }
        self.last_sensor = sensor;
        let s = self.state as usize;
        if start && Self::TR[s][0] >= 0 && self.cycles < 3 {
            self.state = Self::TR[s][0];
            self.fired += 1;
            self.cycles += 1;
        } else if reset && Self::TR[s][2] >= 0 {
            self.state = Self::TR[s][2];
            self.fired += 1;
        }
        self.motor = self.state == 1;
    }
}

#[test]
fn ten_thousand_random_scans_in_lockstep_with_a_rust_model() {
    let (mut p, io) = setup();
    let mut model = Model::default();
    let mut seed: u64 = 0x2545_F491_4F6C_DD1D;
    let mut faults = 0;
    for k in 0..10_000 {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        let inputs = [
            seed & 1 != 0,
            seed & 6 == 6,
            seed & 24 == 24,
            seed & 0x1E0 == 0x1E0,
        ];
        let expected = model.scan(inputs);
        assert_eq!(
            scan(&mut p, &io, inputs),
            expected,
            "scan {k}, inputs {inputs:?}"
        );
        faults += usize::from(expected.1);
    }
    assert!(faults > 0, "the random inputs reach the fault mode");
}
