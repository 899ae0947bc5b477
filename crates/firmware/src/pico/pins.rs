//! GPIO: the pins of the generated pin map (`program::board`), configured
//! once and kept as type-erased rp2040-hal pins (embedded-hal 1.0 pins) in
//! the scan loop's [`Pins`], indexed like the input and output images.
//!
//! Every GPIO of the bank goes through [`configure`]; which input or
//! output (if any) it carries is looked up in the pin map, and an unused
//! pin stays in its reset state. The pins the firmware keeps for itself
//! (`MCU.reserved`: GP23, GP24, GP29 on the Pico; with feature
//! `field-update` also GP0 and GP1, the link's) are never offered:
//! validation refuses them too, and a const assertion below makes a
//! hand-edited pin map fail to build.

use crate::scan::{idle_state, Pins};
use firmware::program::board::{self, SignalPin, INPUT_PINS, OUTPUT_PINS};
use firmware::MCU;
use rp2040_hal::gpio::{
    DynPinId, DynPullType, FunctionNull, FunctionSioInput, FunctionSioOutput, Pin, PinId, PullDown,
    PullNone, ValidFunction,
};

/// An input pin: SIO input with its pull set at run time.
pub type InputPin = Pin<DynPinId, FunctionSioInput, DynPullType>;
/// An output pin: SIO push-pull output, no pull.
pub type OutputPin = Pin<DynPinId, FunctionSioOutput, PullNone>;
/// The configured pins: one slot per input and per output.
pub type Io = Pins<InputPin, OutputPin>;

/// Whether `spec` is GPIO `n`.
const fn is_gpio(spec: &Option<SignalPin>, n: u8) -> bool {
    match spec {
        Some(s) => s.pin.port == boards::PinId::BANK && s.pin.number == n,
        None => false,
    }
}

/// Signals of the pin map: its inputs, then its outputs.
const SIGNALS: usize = INPUT_PINS.len() + OUTPUT_PINS.len();

/// Signal `i` of the pin map (`i < SIGNALS`): input `i`, then the outputs.
const fn signal(i: usize) -> Option<SignalPin> {
    if i < INPUT_PINS.len() {
        INPUT_PINS[i]
    } else {
        OUTPUT_PINS[i - INPUT_PINS.len()]
    }
}

/// Whether the pin map gives GPIO `n` to a signal.
const fn uses(n: u8) -> bool {
    let mut i = 0;
    while i < SIGNALS {
        if is_gpio(&signal(i), n) {
            return true;
        }
        i += 1;
    }
    false
}

/// Whether the pin map gives a pin the firmware keeps for itself
/// (`MCU.reserved`), or a pin of another chip, to a signal.
const fn a_pin_not_offered() -> bool {
    let mut i = 0;
    while i < SIGNALS {
        if let Some(s) = signal(i) {
            if s.pin.port != boards::PinId::BANK || s.pin.number >= 30 {
                return true;
            }
        }
        i += 1;
    }
    let mut r = 0;
    while r < MCU.reserved.len() {
        if uses(MCU.reserved[r].pin.number) {
            return true;
        }
        r += 1;
    }
    false
}

const _: () = assert!(
    !a_pin_not_offered(),
    "the pin map uses a pin the firmware keeps (GP23, GP24, GP29 on the Pico) or one the RP2040 does not have"
);

fn hal_pull(pull: board::Pull) -> DynPullType {
    match pull {
        board::Pull::None => DynPullType::None,
        board::Pull::Up => DynPullType::Up,
        board::Pull::Down => DynPullType::Down,
    }
}

/// Offers every GPIO of the bank to [`claim`].
macro_rules! claim_pins {
    ($io:ident, $bank:ident, [$($pin:ident = $n:expr),* $(,)?]) => {
        $( claim(&mut $io, $n, $bank.$pin); )*
    };
}

/// The pins the field-update link keeps (feature `field-update`): UART0's
/// TX and RX, GP0 and GP1.
#[cfg(feature = "field-update")]
pub type LinkPins = super::serial::LinkPins;
/// The pins the field-update link keeps: none without feature
/// `field-update`.
#[cfg(not(feature = "field-update"))]
pub type LinkPins = ();

#[cfg(feature = "field-update")]
const _: () = assert!(
    !uses(0) && !uses(1),
    "the pin map uses GP0 or GP1, which the firmware keeps with feature `field-update`: UART0, the field-update link; wire those signals to other pins or build without the feature"
);

/// Configures the pins of the pin map: inputs with their pull resistor,
/// outputs push-pull at the level of signal 0 (the output image before
/// the first scan). With feature `field-update`, GP0 and GP1 are not
/// offered but returned for the link.
pub fn configure(bank: rp2040_hal::gpio::Pins) -> (Io, LinkPins) {
    let mut io = Io::default();
    let link;
    #[cfg(not(feature = "field-update"))]
    {
        claim_pins!(io, bank, [gpio0 = 0, gpio1 = 1]);
        link = ();
    }
    // Nor GP0/GP1 (UART0, the field-update link).
    #[cfg(feature = "field-update")]
    {
        link = (bank.gpio0.reconfigure(), bank.gpio1.reconfigure());
    }
    // GP23, GP24 and GP29 (`MCU.reserved`) are not offered.
    claim_pins!(
        io,
        bank,
        [
            gpio2 = 2,
            gpio3 = 3,
            gpio4 = 4,
            gpio5 = 5,
            gpio6 = 6,
            gpio7 = 7,
            gpio8 = 8,
            gpio9 = 9,
            gpio10 = 10,
            gpio11 = 11,
            gpio12 = 12,
            gpio13 = 13,
            gpio14 = 14,
            gpio15 = 15,
            gpio16 = 16,
            gpio17 = 17,
            gpio18 = 18,
            gpio19 = 19,
            gpio20 = 20,
            gpio21 = 21,
            gpio22 = 22,
            gpio25 = 25,
            gpio26 = 26,
            gpio27 = 27,
            gpio28 = 28,
        ]
    );
    (io, link)
}

/// Configures GPIO `n` for the signal it carries, if any.
fn claim<I>(io: &mut Io, n: u8, pin: Pin<I, FunctionNull, PullDown>)
where
    I: PinId + ValidFunction<FunctionSioInput> + ValidFunction<FunctionSioOutput>,
{
    if let Some(i) = INPUT_PINS.iter().position(|s| is_gpio(s, n)) {
        if let Some(spec) = INPUT_PINS[i] {
            let mut pin = pin.reconfigure::<FunctionSioInput, DynPullType>();
            pin.set_pull_type(hal_pull(spec.pull));
            io.inputs[i] = Some(pin.into_dyn_pin());
        }
    } else if let Some(o) = OUTPUT_PINS.iter().position(|s| is_gpio(s, n)) {
        if let Some(spec) = OUTPUT_PINS[o] {
            let pin = pin
                .into_pull_type::<PullNone>()
                .into_push_pull_output_in_state(idle_state(&spec));
            io.outputs[o] = Some(pin.into_dyn_pin());
        }
    }
}
