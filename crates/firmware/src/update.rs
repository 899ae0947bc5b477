//! Field update on the firmware's side: what a loaded image must pass
//! before it runs ([`ImageCheck`], the [`field_update::slot::Check`] the
//! loader and start-up ask), the memory a loaded program runs in
//! ([`Room`]), and the program made from a checked image ([`Loaded`]).
//!
//! A loaded image is judged first by its slot header's wiring signature,
//! which must be this firmware's (`codegen::board::wiring_signature` of
//! the built-in project: the same chip, and inputs and outputs of the
//! same names, pins and levels) and its CRC, by
//! `field_update::slot::accept`; then by everything a generator proves
//! (`executor::parse::load`: parse, then `validate_generated`), then by
//! what this firmware can run: its inputs and outputs are as many as the
//! built-in program's, and its sizes fit [`Room`].

use executor::memory::BoundedMemory;
use executor::parse::{self, Refusal};
use executor::table::{SupervisorTable, TableProgram};
use executor::{Config, Program};
use field_update::slot::Check;

/// Most supervisors (tables) a loaded program may have.
pub const MAX_SUPERVISORS: usize = 16;

/// Longest project name a loaded program may have, in bytes.
pub const MAX_NAME: usize = 64;

/// The memory a loaded program runs in: room for up to 128 inputs (4
/// words), 32 of them debounced, 64 outputs, 32 timers, 16 supervisors
/// and 256 events (8 words; 128 words of allowed sets). About 2.2 KB of
/// RAM.
pub type Room = BoundedMemory<4, 32, 64, 32, MAX_SUPERVISORS, 256, 8, 128>;

/// The image needs more memory than [`Room`] has.
pub const REFUSED_NO_ROOM: u16 = 0x400;
/// The image has another number of inputs than the built-in program.
pub const REFUSED_INPUTS: u16 = 0x401;
/// The image has another number of outputs than the built-in program.
pub const REFUSED_OUTPUTS: u16 = 0x402;

/// The firmware's verdict on an image: the executor's checks, then the
/// board's (inputs and outputs as the built-in program's, room).
/// Refusal codes: [`Refusal::code`] (`0x100`–`0x3ff`), then the
/// `REFUSED_*` codes of this module.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ImageCheck {
    inputs: usize,
    outputs: usize,
    wiring: u32,
}

impl ImageCheck {
    /// The check of a firmware whose built-in program is `built_in`, of
    /// wiring signature `wiring` (the generated `program::board::WIRING`).
    pub fn new(built_in: &Config<'_>, wiring: u32) -> ImageCheck {
        ImageCheck {
            inputs: built_in.inputs.len(),
            outputs: built_in.outputs.len(),
            wiring,
        }
    }

    /// The board's part of the check, on a parsed and validated program.
    fn fits(&self, config: &Config<'_>) -> Result<(), u16> {
        if config.inputs.len() != self.inputs {
            return Err(REFUSED_INPUTS);
        }
        if config.outputs.len() != self.outputs {
            return Err(REFUSED_OUTPUTS);
        }
        if !Room::has_room(config) {
            return Err(REFUSED_NO_ROOM);
        }
        Ok(())
    }
}

impl Check for ImageCheck {
    fn wiring(&self) -> u32 {
        self.wiring
    }

    fn check(&mut self, image: &[u32]) -> Result<(), u16> {
        let mut name = [0u8; MAX_NAME];
        let mut tables = [SupervisorTable::EMPTY; MAX_SUPERVISORS];
        let program = parse::load(image, &mut name, &mut tables, 0).map_err(|r| r.code())?;
        self.fits(&program.config())
    }
}

/// The buffers a program loaded from an image borrows: its name and its
/// tables (the image's words stay where they are).
#[derive(Debug)]
pub struct Loaded<'a> {
    name: [u8; MAX_NAME],
    tables: [SupervisorTable<'a>; MAX_SUPERVISORS],
}

impl Default for Loaded<'_> {
    fn default() -> Self {
        Loaded::new()
    }
}

impl<'a> Loaded<'a> {
    /// Empty buffers.
    pub const fn new() -> Loaded<'a> {
        Loaded {
            name: [0; MAX_NAME],
            tables: [SupervisorTable::EMPTY; MAX_SUPERVISORS],
        }
    }

    /// The program of `image` and its memory: `image` holds the words
    /// [`ImageCheck`] accepted in a slot whose header records `crc`,
    /// parsed again but not judged again (`executor::parse::reload`); the
    /// controller made of it checks their CRC against `crc` and starts in
    /// fault mode on other words. The board's part of the check is
    /// repeated (a few comparisons).
    pub fn program(
        &'a mut self,
        image: &'a [u32],
        crc: u32,
        check: &ImageCheck,
    ) -> Result<(TableProgram<'a>, Room), u16> {
        let program = parse::reload(image, &mut self.name, &mut self.tables, crc)
            .map_err(|r: Refusal| r.code())?;
        let config = program.config();
        check.fits(&config)?;
        let mut room = Room::new();
        if !room.size_for(&config) {
            return Err(REFUSED_NO_ROOM);
        }
        Ok((program, room))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::program;

    /// A wiring signature for the tests (the check's own is compared by
    /// `field_update::slot::accept`, tested there).
    const WIRING: u32 = 0x0005_EED5;

    /// The built-in program's image words (the default project's).
    fn own_image() -> Vec<u32> {
        let mut words = Vec::new();
        executor::image::for_each_word(&program::PROGRAM, |w| words.push(w));
        words
    }

    #[test]
    fn the_built_in_image_passes_and_loads_as_the_built_in_program() {
        let config = program::PROGRAM.config();
        let mut check = ImageCheck::new(&config, WIRING);
        let image = own_image();
        assert_eq!(check.check(&image), Ok(()));
        let mut loaded = Loaded::new();
        let crc = program::PROGRAM.recorded_crc();
        let (program, _room) = loaded.program(&image, crc, &check).expect("loads");
        assert_eq!(program.config().name, config.name);
        assert_eq!(executor::image::crc(&program), crc);
    }

    #[test]
    fn words_changed_after_the_check_start_the_controller_in_fault_mode() {
        let config = program::PROGRAM.config();
        let mut check = ImageCheck::new(&config, WIRING);
        let image = own_image();
        assert_eq!(check.check(&image), Ok(()));
        let crc = program::PROGRAM.recorded_crc();
        // The last word (a table's) flipped between the check and the
        // switch: parsed again, not judged again, caught by the CRC.
        let mut changed = image.clone();
        *changed.last_mut().expect("words") ^= 1;
        let mut loaded = Loaded::new();
        let (program, room) = loaded.program(&changed, crc, &check).expect("parses");
        let controller = executor::Controller::new_proven(program, room).expect("fits");
        assert_eq!(controller.fault(), Some(executor::Fault::Corrupt));
        let mut loaded = Loaded::new();
        let (program, room) = loaded.program(&image, crc, &check).expect("parses");
        let controller = executor::Controller::new_proven(program, room).expect("fits");
        assert_eq!(controller.fault(), None);
    }

    #[test]
    fn an_image_for_other_wiring_or_too_large_is_refused_with_its_code() {
        let config = program::PROGRAM.config();
        let image = own_image();
        let inputs = config.inputs.len();
        let outputs = config.outputs.len();
        let mut other_inputs = ImageCheck {
            inputs: inputs + 1,
            outputs,
            wiring: WIRING,
        };
        assert_eq!(other_inputs.check(&image), Err(REFUSED_INPUTS));
        let mut other_outputs = ImageCheck {
            inputs,
            outputs: outputs + 1,
            wiring: WIRING,
        };
        assert_eq!(other_outputs.check(&image), Err(REFUSED_OUTPUTS));
        // Room for the program's sizes but one event fewer.
        let events = config.events.len();
        let smaller = executor::memory::BoundedMemory::<4, 32, 64, 32, 16, 0, 8, 128>::has_room;
        assert!(events > 0 && !smaller(&config));
    }

    #[test]
    fn a_damaged_image_is_refused_with_the_executors_code() {
        let config = program::PROGRAM.config();
        let mut check = ImageCheck::new(&config, WIRING);
        let mut image = own_image();
        image.pop();
        let code = check.check(&image).expect_err("short image");
        assert!((0x100..0x400).contains(&code), "{code:#x}");
    }
}
