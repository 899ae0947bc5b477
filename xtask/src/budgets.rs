//! `budgets.toml`: per model, the flash, static RAM and instructions per
//! scan CI allows. Start from measured values with a small margin; raising
//! a budget needs its reason in the commit message.
//!
//! This module only reads the limits and compares numbers with them; the
//! tasks that measure (`qemu`, `size`) use it, never the other way round.

use crate::{root, Result};
use serde::Deserialize;
use std::collections::BTreeMap;

/// The whole file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Budgets {
    /// By model name.
    pub models: BTreeMap<String, ModelBudget>,
}

/// One model's limits; an absent limit is not checked.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelBudget {
    /// The project file, relative to the workspace root.
    pub project: String,
    /// Backends the QEMU replay builds besides the `match` baseline
    /// (default: table and logic). The logic backend is for small
    /// supervisors; a model whose CMSSM would not fit leaves it out.
    #[serde(default = "default_backends")]
    pub backends: Vec<String>,
    /// Whether the `match` backend runs too, as the baseline the report
    /// compares with (default: yes; a project with Petri nets has no
    /// `match` program).
    #[serde(default = "yes")]
    pub baseline: bool,
    /// Whether `cargo xtask size` builds the board firmware for it
    /// (default: yes; a project without a `[board]` section, such as the
    /// testbed with more signals than the board has pins, has none).
    #[serde(default = "yes")]
    pub board: bool,
    /// The QEMU scenario's inputs from a closed-loop run instead of
    /// guided random inputs: `host-sim <inputs_from…> --project PROJECT
    /// --inputs-csv FILE` (`["testbed", "laps"]`). For a model whose
    /// random inputs mostly fault and reset, which is not the work its
    /// budget is for. Empty: random inputs.
    #[serde(default)]
    pub inputs_from: Vec<String>,
    /// Median instructions per scan (QEMU harness, table backend).
    pub instr_median: Option<u64>,
    /// Largest instructions per scan (QEMU harness, table backend).
    pub instr_max: Option<u64>,
    /// Flash of the QEMU harness without its scenario.
    pub qemu_flash: Option<u64>,
    /// Static RAM of the QEMU harness.
    pub qemu_ram: Option<u64>,
    /// Flash of the board firmware (`cargo xtask size`).
    pub board_flash: Option<u64>,
    /// Static RAM of the board firmware.
    pub board_ram: Option<u64>,
    /// The model wired to a Raspberry Pi Pico (a project file with `chip
    /// = "RP2040"`): `cargo xtask size` also builds the RP2040 firmware
    /// (feature `pico`, thumbv6m-none-eabi) for it.
    pub pico_project: Option<String>,
    /// Flash of the RP2040 firmware (the 256-byte second-stage bootloader
    /// included).
    pub pico_flash: Option<u64>,
    /// Static RAM of the RP2040 firmware.
    pub pico_ram: Option<u64>,
    /// Code bytes of the board firmware (Nucleo-F411RE) whose source is
    /// the executor crate, inlined code included (`code_share`).
    pub executor_code: Option<u64>,
}

fn yes() -> bool {
    true
}

fn default_backends() -> Vec<String> {
    vec!["table".into(), "logic".into()]
}

impl Budgets {
    /// Reads `budgets.toml` at the workspace root.
    pub fn load() -> Result<Budgets> {
        let path = root().join("budgets.toml");
        let text =
            std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        toml::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))
    }
}

/// The complaint when `got` is over `limit` (an absent limit is never
/// exceeded).
pub fn over(model: &str, what: &str, got: u64, limit: Option<u64>) -> Option<String> {
    limit
        .filter(|&limit| got > limit)
        .map(|limit| format!("{model}: {what} {got} over its budget {limit}"))
}

impl ModelBudget {
    /// Environment variables the harness checks budgets from.
    pub const HARNESS_VARS: [&'static str; 4] = [
        "PLC_BUDGET_FLASH",
        "PLC_BUDGET_RAM",
        "PLC_BUDGET_INSTR_MEDIAN",
        "PLC_BUDGET_INSTR_MAX",
    ];

    /// A model without limits.
    pub fn unbounded(project: &str) -> ModelBudget {
        ModelBudget {
            project: project.to_owned(),
            backends: default_backends(),
            baseline: true,
            board: true,
            inputs_from: Vec::new(),
            instr_median: None,
            instr_max: None,
            qemu_flash: None,
            qemu_ram: None,
            board_flash: None,
            board_ram: None,
            pico_project: None,
            pico_flash: None,
            pico_ram: None,
            executor_code: None,
        }
    }

    /// The harness's budget variables that are set.
    pub fn harness_env(&self) -> Vec<(&'static str, u64)> {
        [
            self.qemu_flash,
            self.qemu_ram,
            self.instr_median,
            self.instr_max,
        ]
        .into_iter()
        .zip(Self::HARNESS_VARS)
        .filter_map(|(v, k)| v.map(|v| (k, v)))
        .collect()
    }

    /// Violations of the board budgets (`pico`: the RP2040 firmware's).
    pub fn check_board(&self, model: &str, pico: bool, flash: u64, ram: u64) -> Vec<String> {
        let (what_flash, budget_flash, what_ram, budget_ram) = if pico {
            (
                "pico flash",
                self.pico_flash,
                "pico static RAM",
                self.pico_ram,
            )
        } else {
            (
                "board flash",
                self.board_flash,
                "board static RAM",
                self.board_ram,
            )
        };
        [
            over(model, what_flash, flash, budget_flash),
            over(model, what_ram, ram, budget_ram),
        ]
        .into_iter()
        .flatten()
        .collect()
    }

    /// The QEMU budgets as text.
    pub fn describe_qemu(&self) -> String {
        let show = |v: Option<u64>| v.map_or("-".to_owned(), |v| v.to_string());
        format!(
            "instr median ≤ {}, max ≤ {}, flash ≤ {}, ram ≤ {}",
            show(self.instr_median),
            show(self.instr_max),
            show(self.qemu_flash),
            show(self.qemu_ram)
        )
    }
}
