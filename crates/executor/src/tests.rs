//! The scan cycle on a small conveyor: a light sensor `ls` starts the
//! belt, its falling edge stops it and starts a 1 s "clear" timer.
//!
//! Supervisor `belt`: 0 -ls_on-> 1 -start-> 2 -ls_off-> 3 -stop-> 0, with
//! `cleared` (timer expiry) in no alphabet.

extern crate std;

use crate::memory::StaticMemory;
use crate::pacing::Pacer;
use crate::program::leak::{records, words};
use crate::program::*;
use crate::table::SupervisorTable;
use crate::{Controller, Fault};
use std::boxed::Box;

const LS: Index = 0;
const RESET: Index = 1;
const AUTO: Index = 2;
const BELT: usize = 0;
const RUNNING_LAMP: usize = 1;

const LS_ON: Index = 0;
const LS_OFF: Index = 1;
const CLEARED: Index = 2;
const START: Index = 3;
const STOP: Index = 4;

struct Conveyor {
    config: Config<'static>,
    /// The CRC recorded for the image is its CRC (else its complement).
    intact: bool,
}

/// Input masks: `ls` (the edges of `ls_on`, `ls_off` and the debounce
/// mask when `ls` is debounced).
const INPUT_MASKS: [u32; 1] = [1 << LS];
/// Events raised by `ls` (0–1) and by the timer (2); the alphabet of
/// `belt` in its local order (3–6); the command with a request input (7).
const EVENT_LISTS: [u32; 8] = [
    LS_ON as u32,
    LS_OFF as u32,
    CLEARED as u32,
    LS_ON as u32,
    START as u32,
    LS_OFF as u32,
    STOP as u32,
    START as u32,
];
/// What `belt` never blocks (0); the commands without a request input,
/// with (1) and without (2) a request input on `start`.
const EVENT_MASKS: [u32; 3] = [1 << CLEARED, 1 << STOP, 1 << START | 1 << STOP];
const ACTIONS: [Action; 3] = [Action::Start(0), Action::Set(0), Action::Clear(0)];
const MEMBERS: [Membership; 4] = [
    Membership {
        supervisor: 0,
        local: 0,
    },
    Membership {
        supervisor: 0,
        local: 1,
    },
    Membership {
        supervisor: 0,
        local: 2,
    },
    Membership {
        supervisor: 0,
        local: 3,
    },
];

fn event(trigger: Trigger, actions: Span, members: Span) -> EventSpec {
    EventSpec {
        trigger,
        when: Span::EMPTY,
        unless: Span::EMPTY,
        request: None,
        actions,
        members,
    }
}

fn config(debounce: u8, policy: UnexpectedPolicy, request: Option<Index>) -> Config<'static> {
    let events = records(&[
        event(
            Trigger::Rising(Span::new(0, 1)),
            Span::EMPTY,
            Span::new(0, 1),
        ),
        event(
            Trigger::Falling(Span::new(0, 1)),
            Span::new(0, 1),
            Span::new(2, 1),
        ),
        event(Trigger::Expired(0), Span::EMPTY, Span::EMPTY),
        EventSpec {
            request,
            ..event(Trigger::Command, Span::new(1, 1), Span::new(1, 1))
        },
        event(Trigger::Command, Span::new(2, 1), Span::new(3, 1)),
    ]);
    let inputs = records(&[
        InputSpec {
            debounce_scans: debounce,
            raises: Span::new(0, 2),
        },
        InputSpec {
            debounce_scans: 0,
            raises: Span::EMPTY,
        },
        InputSpec {
            debounce_scans: 0,
            raises: Span::EMPTY,
        },
    ]);
    let debounced = debounce >= 2;
    Config {
        name: "conveyor",
        scan_period_ms: 10,
        max_commands_per_scan: 1,
        unexpected: policy,
        reset: Some(RESET),
        overrun_limit: 1,
        overrun_fault: false,
        lost_edge_fault: true,
        rom_test_bytes_per_scan: 64,
        inputs,
        debounced: if debounced { &[LS as u32] } else { &[] },
        debounce_mask: if debounced {
            Span::new(0, 1)
        } else {
            Span::EMPTY
        },
        outputs: records(&[
            OutputSpec {
                safe: false,
                initial: false,
                state_map: Span::EMPTY,
            },
            OutputSpec {
                safe: true,
                initial: false,
                state_map: Span { start: 0, len: 1 },
            },
        ]),
        timers: records(&[TimerSpec {
            preset_ms: 1000,
            raises: Span { start: 2, len: 1 },
        }]),
        events,
        supervisors: records(&[SupervisorSpec {
            states: 4,
            initial: 0,
            alphabet: Span { start: 3, len: 4 },
            outside: Span { start: 0, len: 1 },
            allowed: AllowedSets::COMPUTED,
            contiguous: false,
        }]),
        input_masks: &INPUT_MASKS,
        event_lists: &EVENT_LISTS,
        event_masks: &EVENT_MASKS,
        commands: if request.is_some() {
            Span::new(1, 1)
        } else {
            Span::new(2, 1)
        },
        requested: if request.is_some() {
            Span::new(7, 1)
        } else {
            Span::EMPTY
        },
        actions: words(&ACTIONS),
        memberships: words(&MEMBERS),
        state_map: records(&[StateMapEntry {
            supervisor: 0,
            state: 2,
            mask: u32::MAX,
        }]),
        guards: Guards::NONE,
        allowed_index: &[],
    }
}

impl Program for Conveyor {
    fn config(&self) -> Config<'_> {
        self.config
    }

    fn next_state(&self, _supervisor: Index, state: u32, local: Index) -> Option<u32> {
        match (state, local) {
            (0, 0) => Some(1),
            (1, 1) => Some(2),
            (2, 2) => Some(3),
            (3, 3) => Some(0),
            _ => None,
        }
    }

    fn table(&self, _supervisor: Index) -> Option<SupervisorTable<'_>> {
        None
    }

    fn recorded_crc(&self) -> u32 {
        let crc = crate::image::config_crc(&self.config);
        if self.intact {
            crc
        } else {
            !crc
        }
    }
}

/// 3 inputs (1 word), none debounced, 2 outputs, 1 timer, 1 supervisor,
/// 5 events (1 word).
type Mem = StaticMemory<1, 0, 2, 1, 1, 5, 1, 1>;
/// The same with `ls` debounced.
type DebouncedMem = StaticMemory<1, 1, 2, 1, 1, 5, 1, 1>;

fn controller(config: Config<'static>) -> Controller<Conveyor, Mem> {
    Controller::new(
        Conveyor {
            config,
            intact: true,
        },
        Mem::new(),
    )
    .unwrap()
}

fn debounced(config: Config<'static>) -> Controller<Conveyor, DebouncedMem> {
    Controller::new(
        Conveyor {
            config,
            intact: true,
        },
        DebouncedMem::new(),
    )
    .unwrap()
}

fn plain() -> Controller<Conveyor, Mem> {
    controller(config(0, UnexpectedPolicy::Fault, None))
}

/// Inputs (ls, reset, auto).
fn io(ls: bool, reset: bool) -> [bool; 3] {
    [ls, reset, true]
}

#[test]
fn scan_zero_has_no_edges_even_with_the_sensor_already_on() {
    let mut c = plain();
    let r = c.scan(0, &io(true, false));
    assert!(r.executed.is_empty());
    assert_eq!(r.states, [0]);
    assert_eq!(r.scan, 0);
}

#[test]
fn an_edge_runs_its_event_then_one_command_in_the_same_scan() {
    let mut c = plain();
    c.scan(0, &io(false, false));
    let r = c.scan(10, &io(true, false));
    assert_eq!(r.executed, [LS_ON, START]);
    assert_eq!(r.states, [2]);
    assert_eq!((r.outputs[BELT], r.outputs[RUNNING_LAMP]), (true, true));
    assert_eq!(r.fault, None);
}

#[test]
fn falling_edge_starts_a_timer_that_expires_no_earlier_than_its_preset() {
    let mut c = plain();
    c.scan(0, &io(false, false));
    c.scan(10, &io(true, false));
    let r = c.scan(20, &io(false, false));
    assert_eq!(r.executed, [LS_OFF, STOP]);
    assert!(!r.outputs[BELT]);
    assert_eq!(c.timer_deadline(0), Some(1020));
    assert!(c.scan(1019, &io(false, false)).executed.is_empty());
    assert_eq!(c.timer_deadline(0), Some(1020));
    assert_eq!(c.scan(1020, &io(false, false)).executed, [CLEARED]);
    assert_eq!(c.timer_deadline(0), None, "stopped once expired");
    assert_eq!(c.timer_deadline(1), None, "no such timer");
    assert!(
        c.scan(3000, &io(false, false)).executed.is_empty(),
        "expires once"
    );
}

#[test]
fn timers_work_across_the_wrap_of_the_millisecond_clock() {
    let mut c = plain();
    let t0 = u32::MAX - 15;
    c.scan(t0, &io(false, false));
    c.scan(t0.wrapping_add(5), &io(true, false));
    c.scan(t0.wrapping_add(10), &io(false, false)); // timer started
    assert!(c
        .scan(t0.wrapping_add(1009), &io(false, false))
        .executed
        .is_empty());
    assert_eq!(
        c.scan(t0.wrapping_add(1010), &io(false, false)).executed,
        [CLEARED]
    );
}

#[test]
fn unexpected_event_faults_with_safe_outputs_until_reset_rises() {
    let mut c = plain();
    c.scan(0, &io(true, false));
    // The sensor falls in state 0, where no transition explains it.
    let r = c.scan(10, &io(false, false));
    assert_eq!(r.fault, Some(Fault::Unexpected { event: LS_OFF }));
    assert_eq!(r.unexpected, [LS_OFF]);
    assert!(r.executed.is_empty());
    assert_eq!(r.outputs, [false, true], "safe image");
    // Stays faulted, edges ignored.
    let r = c.scan(20, &io(true, false));
    assert_eq!(r.fault, Some(Fault::Unexpected { event: LS_OFF }));
    assert!(r.executed.is_empty());
    assert_eq!(r.outputs, [false, true]);
    // Reset rising: re-initialised image, no fault cause, no events.
    let r = c.scan(30, &io(false, true));
    assert_eq!(r.fault, None);
    assert!(r.executed.is_empty());
    assert_eq!(r.states, [0]);
    assert_eq!(r.outputs, [false, false]);
    assert_eq!(c.scan(40, &io(true, true)).executed, [LS_ON, START]);
    assert_eq!(c.counters().faults, 1);
}

#[test]
fn ignore_policy_drops_and_counts_unexpected_events() {
    let mut c = controller(config(0, UnexpectedPolicy::Ignore, None));
    c.scan(0, &io(true, false));
    let r = c.scan(10, &io(false, false));
    assert_eq!(r.fault, None);
    assert_eq!(r.unexpected, [LS_OFF]);
    assert!(r.executed.is_empty());
    assert_eq!(c.counters().ignored, 1);
}

#[test]
fn debounce_needs_d_consecutive_differing_scans() {
    let mut c = debounced(config(3, UnexpectedPolicy::Fault, None));
    c.scan(0, &io(false, false));
    assert!(c.scan(10, &io(true, false)).executed.is_empty());
    assert!(c.scan(20, &io(true, false)).executed.is_empty());
    // A bounce back to 0 restarts the count.
    assert!(c.scan(30, &io(false, false)).executed.is_empty());
    assert!(c.scan(40, &io(true, false)).executed.is_empty());
    assert!(c.scan(50, &io(true, false)).executed.is_empty());
    assert_eq!(c.scan(60, &io(true, false)).executed, [LS_ON, START]);
}

#[test]
fn a_command_with_a_request_input_waits_for_it() {
    let mut c = controller(config(0, UnexpectedPolicy::Fault, Some(AUTO)));
    c.scan(0, &[false, false, false]);
    assert_eq!(c.scan(10, &[true, false, false]).executed, [LS_ON]);
    assert!(c.scan(20, &[true, false, false]).executed.is_empty());
    assert_eq!(c.scan(30, &[true, false, true]).executed, [START]);
}

#[test]
fn commands_of_any_word_are_worked_out_alike_cached_or_one_word_at_a_time() {
    use crate::controller::{commands_word, Commands, CACHED_COMMAND_WORDS};
    // 300 commands (10 words: past the 8 a scan caches), those of word 9
    // and of word 0 requested by `auto`; the unrequested commands' mask.
    let mut specs = std::vec![event(Trigger::Command, Span::EMPTY, Span::EMPTY); 300];
    for e in [3, 40, 290, 299] {
        specs[e].request = Some(AUTO);
    }
    let masks: std::vec::Vec<u32> = (0..10).map(|k| 0x8000_0001 >> (k % 2)).collect();
    let config = Config {
        events: records(&specs),
        event_masks: Box::leak(masks.into_boxed_slice()),
        event_lists: &[3, 40, 290, 299],
        commands: Span::new(0, 10),
        requested: Span::new(0, 4),
        ..config(0, UnexpectedPolicy::Fault, None)
    };
    for auto in [false, true] {
        let mut memory = StaticMemory::<1, 0, 0, 0, 0, 0, 0, 0>::new();
        let ram = crate::memory::sealed::Storage::ram(&mut memory);
        ram.filtered[0] = u32::from(auto) << AUTO;
        let requested = |bits: u32| if auto { bits } else { 0 };
        let cached = Commands::now(&config, &ram);
        let words: std::vec::Vec<u32> = (0..11).map(|k| cached.word(&config, &ram, k)).collect();
        assert_eq!(words[0], 0x8000_0001 | requested(1 << 3));
        assert_eq!(words[1], 0x4000_0000 | requested(1 << 8));
        assert_eq!(words[9], 0x4000_0000 | requested(1 << 2 | 1 << 11));
        assert_eq!(words[10], 0);
        for (k, &word) in words.iter().enumerate() {
            assert_eq!(
                commands_word(&config, &ram, k),
                word,
                "word {k}, auto {auto}"
            );
        }
        assert!(words.len() > CACHED_COMMAND_WORDS);
    }
}

/// `new_proven` of the conveyor, its CRC recorded as `intact` says.
fn proven(config: Config<'static>, intact: bool) -> Controller<Conveyor, Mem> {
    Controller::new_proven(Conveyor { config, intact }, Mem::new()).unwrap()
}

#[test]
fn a_proven_image_whose_crc_matches_runs_as_a_checked_one() {
    let config = config(0, UnexpectedPolicy::Fault, Some(AUTO));
    let (mut checked, mut trusted) = (controller(config), proven(config, true));
    assert_eq!(trusted.fault(), None);
    for k in 0..64u32 {
        let io = [k % 3 == 1, k % 17 == 9, k % 5 != 0];
        let now = 10 * k;
        let want = checked.scan(now, &io);
        let (fault, outputs, executed) =
            (want.fault, want.outputs.to_vec(), want.executed.to_vec());
        let got = trusted.scan(now, &io);
        assert_eq!(
            (got.fault, got.outputs, got.executed),
            (fault, &outputs[..], &executed[..]),
            "scan {k}"
        );
    }
}

#[test]
fn a_proven_image_whose_crc_does_not_match_never_runs_even_malformed() {
    // Flaws the structure check would refuse, each in an image whose CRC
    // does not match: nothing of it may run, no scan may panic, and the
    // outputs stay at their safe levels through resets.
    let base = || config(2, UnexpectedPolicy::Fault, Some(AUTO));
    let mut flawed: std::vec::Vec<Config<'static>> = std::vec![base()];
    flawed.push(Config {
        reset: Some(40),
        ..base()
    });
    flawed.push(Config {
        debounced: &[77],
        ..base()
    });
    flawed.push(Config {
        actions: words(&[Action::Start(9), Action::Set(7), Action::Clear(0)]),
        ..base()
    });
    flawed.push(Config {
        memberships: words(
            &[Membership {
                supervisor: 5,
                local: 9,
            }; 4],
        ),
        ..base()
    });
    flawed.push(Config {
        commands: Span::new(9, 4),
        requested: Span::new(30, 2),
        ..base()
    });
    flawed.push(Config {
        supervisors: records(&[SupervisorSpec {
            states: 0,
            initial: 9,
            alphabet: Span::new(6, 9),
            outside: Span::new(8, 3),
            allowed: AllowedSets::COMPUTED,
            contiguous: true,
        }]),
        ..base()
    });
    for (n, config) in flawed.into_iter().enumerate() {
        let conveyor = Conveyor {
            config,
            intact: false,
        };
        let mut c = Controller::new_proven(conveyor, DebouncedMem::new()).unwrap();
        assert_eq!(c.fault(), Some(Fault::Corrupt), "image {n}");
        for k in 0..48u32 {
            let r = c.scan(10 * k, &[k % 2 == 1, k % 4 >= 2, k % 8 >= 4]);
            assert_eq!(r.fault, Some(Fault::Corrupt), "image {n}, scan {k}");
            assert!(r.executed.is_empty(), "image {n}, scan {k}");
            assert_eq!(r.outputs, [false, true], "image {n}, scan {k}");
        }
    }
}

/// A CRC engine lent to one controller after another, as a field-update
/// firmware lends its CRC unit (`impl CrcEngine for &mut E`): it counts
/// the words it is fed.
struct Counted(usize);

impl crate::image::CrcEngine for Counted {
    fn feed(&mut self, crc: u32, words: &[u32]) -> u32 {
        self.0 += words.len();
        crate::image::TableCrc.feed(crc, words)
    }
}

#[test]
fn new_with_crc_checks_the_structure_and_a_lent_engine_serves_each_controller() {
    let mut engine = Counted(0);
    let conveyor = |config, intact| Conveyor { config, intact };
    let sound = config(0, UnexpectedPolicy::Fault, None);
    // A sound image on the lent engine runs as with the default one.
    {
        let mut lent =
            Controller::new_with_crc(conveyor(sound, true), Mem::new(), &mut engine).unwrap();
        let mut own = plain();
        assert_eq!(lent.fault(), None);
        for k in 0..32u32 {
            let io = io(k % 4 == 1, false);
            let want = own.scan(10 * k, &io);
            let want = (want.fault, want.outputs.to_vec(), want.executed.to_vec());
            let got = lent.scan(10 * k, &io);
            assert_eq!(
                (got.fault, got.outputs.to_vec(), got.executed.to_vec()),
                want,
                "scan {k}"
            );
        }
        assert!(lent.check_image());
    }
    let fed = engine.0;
    assert!(
        fed > 0,
        "the start-up check, the shares and check_image ran on the engine"
    );
    // A flaw of structure under a matching CRC: `new_with_crc` refuses to
    // run it, as `new` does; `new_proven_with_crc` trusts the CRC.
    let flawed = Config {
        reset: Some(40),
        ..sound
    };
    let checked =
        Controller::new_with_crc(conveyor(flawed, true), Mem::new(), &mut engine).unwrap();
    assert_eq!(checked.fault(), Some(Fault::Corrupt));
    assert!(
        engine.0 > fed,
        "the next controller's check ran on the same engine"
    );
    let trusted =
        Controller::new_proven_with_crc(conveyor(flawed, true), Mem::new(), &mut engine).unwrap();
    assert_eq!(trusted.fault(), None);
    // And a CRC that does not match is a fault on any engine.
    let mismatch =
        Controller::new_with_crc(conveyor(sound, false), Mem::new(), &mut engine).unwrap();
    assert_eq!(mismatch.fault(), Some(Fault::Corrupt));
}

#[test]
fn a_corrupt_image_starts_in_fault_mode_and_reset_cannot_clear_it() {
    let config = config(0, UnexpectedPolicy::Fault, None);
    let mut c = Controller::new(
        Conveyor {
            config,
            intact: false,
        },
        Mem::new(),
    )
    .unwrap();
    assert_eq!(c.fault(), Some(Fault::Corrupt));
    c.scan(0, &io(false, false));
    let r = c.scan(10, &io(false, true));
    assert_eq!(r.fault, Some(Fault::Corrupt));
    assert_eq!(r.outputs, [false, true]);
}

#[test]
fn lost_edges_are_faults_when_configured_and_overruns_only_counted() {
    let mut c = plain();
    c.scan(0, &io(false, false));
    c.report_overrun();
    assert_eq!(c.scan(10, &io(false, false)).fault, None);
    c.report_lost_edge();
    assert_eq!(c.scan(20, &io(false, false)).fault, Some(Fault::LostEdge));
    let n = c.counters();
    assert_eq!((n.overruns, n.lost_edges, n.faults), (1, 1, 1));
}

#[test]
fn a_scan_found_due_late_counts_skipped_periods_and_overruns_beyond_the_limit() {
    // Period 10 ms, overrun_limit 1: up to 10 ms late is on time.
    let mut c = plain();
    let mut pacer = Pacer::for_config(&c.program().config(), 0);
    assert_eq!(c.scan_due(&mut pacer, 0).map(|s| s.late_ms), Some(0));
    c.scan(0, &io(false, false));
    assert_eq!(c.scan_due(&mut pacer, 9), None);
    let start = c.scan_due(&mut pacer, 20).unwrap();
    assert_eq!(
        (start.late_ms, start.skipped, start.overrun),
        (10, 1, false)
    );
    c.scan(start.time_ms, &io(false, false));
    let start = c.scan_due(&mut pacer, 55).unwrap();
    assert_eq!((start.late_ms, start.skipped, start.overrun), (25, 2, true));
    // overrun_fault = false: counted only.
    assert_eq!(c.scan(55, &io(false, false)).fault, None);
    let n = c.counters();
    assert_eq!((n.skipped_periods, n.overruns, n.faults), (3, 1, 0));
}

#[test]
fn an_overrun_is_a_fault_from_its_own_scan_when_configured() {
    let mut c = controller(Config {
        overrun_fault: true,
        ..config(0, UnexpectedPolicy::Fault, None)
    });
    let mut pacer = Pacer::for_config(&c.program().config(), 0);
    c.scan_due(&mut pacer, 0).unwrap();
    c.scan(0, &io(false, false));
    assert!(!c.scan_due(&mut pacer, 20).unwrap().overrun);
    assert_eq!(c.scan(20, &io(false, false)).fault, None);
    assert!(c.scan_due(&mut pacer, 41).unwrap().overrun);
    assert_eq!(c.fault(), Some(Fault::Overrun));
    let r = c.scan(41, &io(false, false));
    assert_eq!(
        (r.fault, r.outputs),
        (Some(Fault::Overrun), &[false, true][..])
    );
}

#[test]
fn memory_of_the_wrong_size_is_refused() {
    let config = config(0, UnexpectedPolicy::Fault, None);
    let small: StaticMemory<1, 0, 2, 1, 1, 4, 1, 1> = StaticMemory::new();
    assert!(Controller::new(
        Conveyor {
            config,
            intact: true
        },
        small
    )
    .is_err());
}

#[test]
fn bounded_memory_runs_a_program_that_fits_as_memory_of_its_exact_size() {
    use crate::memory::BoundedMemory;
    let config = config(0, UnexpectedPolicy::Fault, None);
    let mut room: BoundedMemory<2, 1, 4, 2, 2, 40, 2, 4> = BoundedMemory::new();
    // Not sized yet: refused like memory of the wrong size.
    assert!(Controller::new(
        Conveyor {
            config,
            intact: true
        },
        room.clone()
    )
    .is_err());
    assert!(room.size_for(&config));
    let mut bounded = Controller::new(
        Conveyor {
            config,
            intact: true,
        },
        room,
    )
    .unwrap();
    let mut exact = plain();
    for (k, (ls, reset)) in [(false, false), (true, false), (true, false), (false, false)]
        .into_iter()
        .cycle()
        .take(40)
        .enumerate()
    {
        let t = 10 * k as u32;
        let want = exact.scan(t, &io(ls, reset));
        let want = (
            want.executed.to_vec(),
            want.states.to_vec(),
            want.outputs.to_vec(),
            want.fault,
        );
        let got = bounded.scan(t, &io(ls, reset));
        let got = (
            got.executed.to_vec(),
            got.states.to_vec(),
            got.outputs.to_vec(),
            got.fault,
        );
        assert_eq!(got, want, "scan {k}");
    }
}

#[test]
fn bounded_memory_refuses_a_program_larger_than_its_room() {
    use crate::memory::{BoundedMemory, Memory};
    let config = config(0, UnexpectedPolicy::Fault, None);
    // Room for 4 events: the conveyor has 5.
    let mut room: BoundedMemory<1, 0, 2, 1, 1, 4, 1, 1> = BoundedMemory::new();
    assert!(!room.size_for(&config));
    assert!(!room.fits(&config));
    // Room for every size but the outputs.
    let mut room: BoundedMemory<1, 0, 1, 1, 1, 5, 1, 1> = BoundedMemory::new();
    assert!(!room.size_for(&config));
}

/// Memory corruption (a flipped RAM bit) is simulated by writing the
/// sealed arrays from inside the crate.
#[test]
fn a_state_out_of_range_is_corrupt_within_one_round_of_supervisors() {
    let mut c = plain();
    c.scan(0, &io(false, false));
    use crate::memory::sealed::Storage;
    c.memory.ram().states[0] = 7; // `belt` has 4 states
    let r = c.scan(10, &io(false, false));
    assert_eq!(
        r.fault,
        Some(Fault::Corrupt),
        "one supervisor: the next scan checks it"
    );
    assert_eq!(r.outputs, [false, true], "the safe image");
}

#[test]
fn a_state_out_of_range_is_corrupt_before_the_event_moves_it() {
    let mut c = plain();
    c.scan(0, &io(false, false));
    c.scan(10, &io(false, false));
    use crate::memory::sealed::Storage;
    c.memory.ram().states[0] = 9;
    // Skip the rotating check: the edge of `ls` reaches `execute` first.
    c.range_check = 1;
    let r = c.scan(20, &io(true, false));
    assert_eq!(r.fault, Some(Fault::Corrupt));
    assert!(r.executed.is_empty());
}

#[test]
fn an_enabled_set_corrupted_in_ram_cannot_run_an_event_the_table_refuses() {
    let mut c = plain();
    c.scan(0, &io(false, false));
    assert_eq!(c.states(), [0], "`stop` is not enabled in state 0");
    use crate::memory::sealed::Storage;
    let ram = c.memory.ram();
    ram.allowed[0] |= 1 << STOP;
    ram.feasible[0] |= 1 << STOP;
    // The flipped bit makes `stop` look enabled; a request-free command is
    // chosen as soon as it is feasible, so this scan tries it.
    c.idle = false;
    let r = c.scan(10, &io(false, false));
    assert_eq!(r.fault, Some(Fault::Corrupt));
    assert!(r.executed.is_empty(), "the refused command did not run");
    assert_eq!(r.states, [0]);
}

#[test]
fn quiet_scans_skip_the_controllable_phase_but_not_a_new_request() {
    // `start` waits for its request input `auto` (input 2).
    let mut c = controller(config(0, UnexpectedPolicy::Fault, Some(AUTO)));
    c.scan(0, &[false, false, false]);
    let r = c.scan(10, &[true, false, false]);
    assert_eq!(r.executed, [LS_ON], "no request yet: `start` waits");
    for t in [20, 30, 40] {
        assert!(c.scan(t, &[true, false, false]).executed.is_empty());
        assert!(
            c.idle,
            "nothing to choose: the next quiet scan skips the phase"
        );
    }
    let r = c.scan(50, &[true, false, true]);
    assert_eq!(
        r.executed,
        [START],
        "the request input changed: the phase runs"
    );
    assert!(!c.idle);
}

/// `config` with `stop` guarded by "bit 0 of the belt's state is `bit`".
fn guarded_stop(bit: bool) -> Config<'static> {
    let (low, high) = if bit { (0, 1) } else { (1, 0) };
    Config {
        guards: Guards {
            events: records(&[GuardSpec {
                event: STOP,
                root: 2,
                nodes: Span::new(0, 1),
            }]),
            bits: records(&[StateBit {
                component: 0,
                shift: 0,
            }]),
            nodes: records(&[GuardNode { bit: 0, low, high }]),
        },
        ..config(0, UnexpectedPolicy::Fault, None)
    }
}

#[test]
fn a_guard_that_does_not_hold_keeps_its_command_from_running() {
    // `stop` is enabled by the belt in state 3 (binary 11).
    for (bit, executed) in [(true, &[LS_OFF, STOP][..]), (false, &[LS_OFF][..])] {
        let mut c = controller(guarded_stop(bit));
        c.scan(0, &io(false, false));
        c.scan(10, &io(true, false));
        let r = c.scan(20, &io(false, false));
        assert_eq!(r.executed, executed, "guard `bit 0 = {bit}`");
        assert_eq!(r.fault, None);
    }
}

#[test]
fn the_structure_check_refuses_a_malformed_guard() {
    use crate::validate::{validate_config, Flaw, Part};
    assert_eq!(validate_config(&guarded_stop(true)), Ok(()));
    let with = |f: &dyn Fn(&mut Guards<'static>)| {
        let mut c = guarded_stop(true);
        f(&mut c.guards);
        validate_config(&c).map_err(|e| (e.part, e.flaw))
    };
    let guard = |event, root| {
        records(&[GuardSpec {
            event,
            root,
            nodes: Span::new(0, 1),
        }])
    };
    // On an uncontrollable event.
    assert_eq!(
        with(&|g| g.events = guard(LS_ON, 2)),
        Err((Part::Guard(0), Flaw::Guarded))
    );
    // A root past the nodes.
    assert_eq!(
        with(&|g| g.events = guard(STOP, 3)),
        Err((Part::Guard(0), Flaw::GuardNode { node: 3 }))
    );
    // A node pointing to itself, one reading a missing bit.
    let node = |bit, low| records(&[GuardNode { bit, low, high: 1 }]);
    assert_eq!(
        with(&|g| g.nodes = node(0, 2)),
        Err((Part::Guard(0), Flaw::GuardNode { node: 2 }))
    );
    assert_eq!(
        with(&|g| g.nodes = node(1, 0)),
        Err((Part::Guard(0), Flaw::GuardNode { node: 2 }))
    );
    // A bit of a supervisor that does not exist, a shift past 31.
    assert_eq!(
        with(&|g| g.bits = records(&[StateBit {
            component: 1,
            shift: 0
        }])),
        Err((Part::StateBit(0), Flaw::OutOfRange { index: 1, count: 1 }))
    );
    assert_eq!(
        with(&|g| g.bits = &[[32 << 16]]),
        Err((Part::StateBit(0), Flaw::Shift))
    );
}

/// The belt's allowed sets stored: `cleared` (outside its alphabet) and
/// the one event it enables in each state, sets 3–6 after the pool's
/// three; `index` packs the set numbers of states 0–3 in 3 bits each.
fn stored(index: u32, bits: u8) -> Config<'static> {
    let c = config(0, UnexpectedPolicy::Fault, None);
    let mut masks = EVENT_MASKS.to_vec();
    for e in [LS_ON, START, LS_OFF, STOP] {
        masks.push(1 << CLEARED | 1 << e);
    }
    let supervisors = records(&[SupervisorSpec {
        allowed: AllowedSets {
            index: Span::new(0, 1),
            bits,
        },
        ..c.supervisor(0)
    }]);
    Config {
        supervisors,
        event_masks: Box::leak(masks.into_boxed_slice()),
        allowed_index: Box::leak(Box::new([index])),
        ..c
    }
}

/// Set numbers 3, 4, 5, 6 for states 0–3.
const BELT_INDEX: u32 = 3 | 4 << 3 | 5 << 6 | 6 << 9;

#[test]
fn stored_allowed_sets_give_the_trace_of_computed_ones() {
    let mut computed = plain();
    let mut from_sets = controller(stored(BELT_INDEX, 3));
    assert_eq!(from_sets.fault(), None, "the stored sets pass the check");
    // A pseudo-random sensor, with a reset now and then.
    let mut x = 0x2545_f491_u32;
    let mut ran = 0;
    for scan in 0..2_000u32 {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        let inputs = io(x & 3 == 0, x >> 8 & 31 == 0);
        let a = computed.scan(scan * 10, &inputs);
        let (executed, states, outputs, fault) = (
            a.executed.to_vec(),
            a.states.to_vec(),
            a.outputs.to_vec(),
            a.fault,
        );
        let b = from_sets.scan(scan * 10, &inputs);
        assert_eq!(
            (b.executed, b.states, b.outputs, b.fault),
            (&executed[..], &states[..], &outputs[..], fault),
            "scan {scan}"
        );
        ran += executed.len();
    }
    assert!(ran > 100, "the run moves the belt ({ran} events)");
}

#[test]
fn stored_sets_that_are_not_the_programs_are_refused() {
    use crate::validate::{validate, validate_allowed_sets, Flaw, Part};
    let check = |config: Config<'static>| {
        let program = Conveyor {
            config,
            intact: true,
        };
        validate(&program)
            .and_then(|()| validate_allowed_sets(&program))
            .map_err(|e| (e.part, e.flaw))
    };
    let at = Part::Supervisor(0);
    assert_eq!(check(stored(BELT_INDEX, 3)), Ok(()));
    // State 1 given state 2's set: `ls_off` instead of `start`.
    let swapped = 3 | 5 << 3 | 5 << 6 | 6 << 9;
    assert_eq!(
        check(stored(swapped, 3)),
        Err((at, Flaw::AllowedSet { state: 1 }))
    );
    // The controller's own check leaves that to generation: such a set
    // only holds events back or ends in a `Corrupt` fault.
    let program = Conveyor {
        config: stored(swapped, 3),
        intact: true,
    };
    assert_eq!(validate(&program), Ok(()));
    // A set without `cleared`, outside the alphabet: set 1 is `stop` alone.
    assert_eq!(
        check(stored(3 | 4 << 3 | 5 << 6 | 1 << 9, 3)),
        Err((at, Flaw::AllowedSet { state: 3 }))
    );
    // A set number past the pool, a width of 0 or past 16 bits, an index
    // too long for four 2-bit entries.
    assert_eq!(
        check(stored(BELT_INDEX | 7 << 9, 3)),
        Err((at, Flaw::AllowedIndex))
    );
    assert_eq!(check(stored(BELT_INDEX, 0)), Err((at, Flaw::AllowedIndex)));
    assert_eq!(check(stored(BELT_INDEX, 17)), Err((at, Flaw::AllowedIndex)));
    let long = Config {
        allowed_index: Box::leak(Box::new([BELT_INDEX, 0])),
        supervisors: records(&[SupervisorSpec {
            allowed: AllowedSets {
                index: Span::new(0, 2),
                bits: 3,
            },
            ..stored(BELT_INDEX, 3).supervisor(0)
        }]),
        ..stored(BELT_INDEX, 3)
    };
    assert_eq!(check(long), Err((at, Flaw::AllowedIndex)));
    // A stray bit past the last event in a stored set: the controller
    // could choose it as a command.
    let mut c = stored(BELT_INDEX, 3);
    let mut masks = c.event_masks.to_vec();
    masks[6] |= 1 << 9;
    c.event_masks = Box::leak(masks.into_boxed_slice());
    assert_eq!(check(c), Err((at, Flaw::AllowedIndex)));
}
