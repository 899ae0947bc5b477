//! Figures of a lowered program: what the background image check costs
//! ([`ImageCheck`]) and the event sets a scan keeps ([`ScanSets`]).

use super::config::ConfigPools;
use executor::image as ex_image;
use executor::program::{self as ex, Program};

/// What the background image test costs a program and how fast it finds
/// a flipped bit (docs/semantics.md, "Image check").
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct ImageCheck {
    /// Bytes the image CRC covers.
    pub image_bytes: usize,
    /// Bytes the background test checks per scan.
    pub bytes_per_scan: usize,
    /// The scan period.
    pub scan_period_ms: u32,
}

impl ImageCheck {
    /// The figures of `program`'s image.
    pub fn of<P: Program + ?Sized>(program: &P) -> ImageCheck {
        let config = program.config();
        ImageCheck {
            image_bytes: ex_image::bytes(program),
            bytes_per_scan: usize::from(config.rom_test_bytes_per_scan / 4).max(1) * 4,
            scan_period_ms: config.scan_period_ms,
        }
    }

    /// Scans a background pass takes: ⌈image bytes / bytes per scan⌉.
    pub fn pass_scans(&self) -> usize {
        self.image_bytes.div_ceil(self.bytes_per_scan)
    }

    /// The most scans from a flipped bit to the `Corrupt` fault: 2P − 1,
    /// counting the first scan after the flip as 1.
    pub fn bound_scans(&self) -> usize {
        2 * self.pass_scans() - 1
    }

    /// [`ImageCheck::bound_scans`] in milliseconds at the scan period.
    pub fn bound_ms(&self) -> u64 {
        self.bound_scans() as u64 * u64::from(self.scan_period_ms)
    }
}

/// What the executor keeps to decide feasibility by word operations
/// (docs/architecture.md, "What a scan costs"): the supervisors'
/// alphabets and event sets in flash, one event set per supervisor and the
/// feasible set in RAM. A supervisor that stores its allowed sets has them
/// among the event sets, one per distinct set, with an index by state;
/// the others' enabled events are the tables' rows of defined-bits (or the
/// logic backend's φ functions), counted there.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct ScanSets {
    /// Words of an event set (32 events per word).
    pub event_words: usize,
    /// Flash bytes of the alphabets (local to event number, 2 bytes per
    /// local event).
    pub alphabet_bytes: usize,
    /// Flash bytes of the event masks (what each supervisor never blocks,
    /// the commands, the stored allowed sets).
    pub mask_bytes: usize,
    /// RAM bytes of the sets: one per supervisor, and the feasible set.
    pub ram_bytes: usize,
    /// Supervisors whose allowed sets are stored (`[plc] stored_sets_bytes`).
    pub stored: usize,
    /// All supervisors.
    pub supervisors: usize,
    /// Flash bytes of the stored sets' index (`ALLOWED_INDEX`).
    pub index_bytes: usize,
    /// What the symbolic supervisors' guards cost.
    pub guards: GuardFigures,
}

/// The guards of symbolic supervisors: how many, their size in flash, and
/// the longest walk one takes (decision nodes read, one state bit each).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub struct GuardFigures {
    /// Guarded commands.
    pub guards: usize,
    /// Decision nodes, all guards together.
    pub nodes: usize,
    /// State bits the guards read.
    pub state_bits: usize,
    /// Flash bytes of the guards, nodes and state bits.
    pub bytes: usize,
    /// The most nodes one evaluation of a guard reads.
    pub longest_walk: usize,
}

impl GuardFigures {
    /// The figures of `pools`' guards.
    pub fn of(pools: &ConfigPools) -> GuardFigures {
        let longest_walk = pools
            .guards
            .iter()
            .map(|g| {
                // Children come first: one pass gives every node's depth.
                let nodes = g.nodes.of(&pools.guard_nodes);
                let mut depth = vec![0usize; nodes.len() + 2];
                for (i, n) in nodes.iter().enumerate() {
                    let of = |k: u16| depth.get(usize::from(k)).copied().unwrap_or(0);
                    depth[i + 2] = 1 + of(n.low).max(of(n.high));
                }
                depth.get(usize::from(g.root)).copied().unwrap_or(0)
            })
            .max()
            .unwrap_or(0);
        GuardFigures {
            guards: pools.guards.len(),
            nodes: pools.guard_nodes.len(),
            state_bits: pools.state_bits.len(),
            bytes: size_of::<ex::GuardSpec>() * pools.guards.len()
                + size_of::<ex::GuardNode>() * pools.guard_nodes.len()
                + size_of::<ex::StateBit>() * pools.state_bits.len(),
            longest_walk,
        }
    }
}

impl ScanSets {
    /// The figures of `pools`.
    pub fn of(pools: &ConfigPools) -> ScanSets {
        let event_words = ex::words(pools.events.len());
        let alphabet = pools
            .supervisors
            .iter()
            .map(|s| usize::from(s.alphabet.len))
            .sum::<usize>();
        ScanSets {
            event_words,
            alphabet_bytes: 2 * alphabet,
            mask_bytes: 4 * pools.event_masks.len(),
            ram_bytes: 4 * event_words * (pools.supervisors.len() + 1),
            stored: pools
                .supervisors
                .iter()
                .filter(|s| s.allowed.is_stored())
                .count(),
            supervisors: pools.supervisors.len(),
            index_bytes: 4 * pools.allowed_index.len(),
            guards: GuardFigures::of(pools),
        }
    }
}
