//! GPIO: the pins of the generated pin map (`program::board`), configured
//! once and kept as type-erased HAL pins (embedded-hal 1.0 pins) in the
//! scan loop's [`Pins`], indexed like the input and output images.
//!
//! Every pin of every port goes through [`Io::claim`]; which input or
//! output (if any) it carries is looked up at compile time (`Slot`), so an
//! unused pin costs nothing and stays in its reset state. The pins the
//! firmware keeps for itself (`MCU.reserved`, the board data's: PA13/PA14
//! for SWD, PH0 for the HSE clock input) are never offered: validation
//! refuses them too, and a const assertion below makes a hand-edited pin
//! map fail to build.

use crate::scan::{idle_state, Pins};
use embedded_hal::digital::PinState;
use firmware::program::board::{self, INPUT_PINS, OUTPUT_PINS};
use firmware::MCU;
use stm32f4xx_hal::gpio::{
    self, gpioa, gpiob, gpioc, gpiod, gpioe, gpioh, Edge, ErasedPin, ExtiPin, Input, Output,
    PinMode, PushPull,
};
use stm32f4xx_hal::pac::EXTI;
use stm32f4xx_hal::syscfg::SysCfg;

/// The index of the signal wired to port `port`, pin `n` in `pins`.
const fn find(pins: &[Option<board::SignalPin>], port: char, n: u8) -> Option<usize> {
    let mut i = 0;
    while i < pins.len() {
        if let Some(p) = pins[i] {
            if p.pin.port == port && p.pin.number == n {
                return Some(i);
            }
        }
        i += 1;
    }
    None
}

/// How many entries of `pins` are port `port`, pin `n`.
const fn count(pins: &[Option<board::SignalPin>], port: char, n: u8) -> usize {
    let mut count = 0;
    let mut i = 0;
    while i < pins.len() {
        if let Some(p) = pins[i] {
            if p.pin.port == port && p.pin.number == n {
                count += 1;
            }
        }
        i += 1;
    }
    count
}

/// How many signals of the pin map port `port`, pin `n` carries.
const fn uses(port: char, n: u8) -> usize {
    count(&INPUT_PINS, port, n) + count(&OUTPUT_PINS, port, n)
}

/// Whether the pin map gives a pin the firmware keeps for itself
/// (`MCU.reserved`) to a signal.
const fn a_reserved_pin_used() -> bool {
    let mut r = 0;
    while r < MCU.reserved.len() {
        let pin = MCU.reserved[r].pin;
        if uses(pin.port, pin.number) > 0 {
            return true;
        }
        r += 1;
    }
    false
}

const _: () = assert!(
    !a_reserved_pin_used(),
    "the pin map uses a pin the firmware keeps: PA13/PA14 carry SWD (flashing and the defmt log), PH0 is the HSE clock input"
);

/// Whether some pin of the chip's ports carries two signals.
const fn a_pin_twice() -> bool {
    let mut p = 0;
    while p < MCU.ports.len() {
        let port = &MCU.ports[p];
        let mut n = 0;
        while n < port.pins {
            if uses(port.letter, n) > 1 {
                return true;
            }
            n += 1;
        }
        p += 1;
    }
    false
}

const _: () = assert!(!a_pin_twice(), "a pin carries two signals in the pin map");

/// What pin (P, N) carries, evaluated at compile time per pin.
struct Slot<const P: char, const N: u8>;

impl<const P: char, const N: u8> Slot<P, N> {
    const INPUT: Option<usize> = find(&INPUT_PINS, P, N);
    const OUTPUT: Option<usize> = find(&OUTPUT_PINS, P, N);
}

fn hal_pull(pull: board::Pull) -> gpio::Pull {
    match pull {
        board::Pull::None => gpio::Pull::None,
        board::Pull::Up => gpio::Pull::Up,
        board::Pull::Down => gpio::Pull::Down,
    }
}

/// The GPIO ports, split by the HAL (which enables their clocks).
pub struct Ports {
    /// Port A.
    pub a: gpioa::Parts,
    /// Port B.
    pub b: gpiob::Parts,
    /// Port C.
    pub c: gpioc::Parts,
    /// Port D.
    pub d: gpiod::Parts,
    /// Port E.
    pub e: gpioe::Parts,
    /// Port H.
    pub h: gpioh::Parts,
}

/// Offers every listed pin of a port to [`Io::claim`].
macro_rules! claim_pins {
    ($io:ident, $port:expr, [$($pin:ident),* $(,)?]) => {
        $( $io.claim($port.$pin); )*
    };
}

/// The configured pins: one slot per input and per output.
pub type Io = Pins<ErasedPin<Input>, ErasedPin<Output<PushPull>>>;

/// The pins the field-update link keeps (feature `field-update`): USART2's
/// TX and RX, PA2 and PA3 (the ST-LINK's virtual COM port).
#[cfg(feature = "field-update")]
pub type LinkPins = (gpioa::PA2<Input>, gpioa::PA3<Input>);
/// The pins the field-update link keeps: none without feature
/// `field-update`.
#[cfg(not(feature = "field-update"))]
pub type LinkPins = ();

#[cfg(feature = "field-update")]
const _: () = assert!(
    uses('A', 2) == 0 && uses('A', 3) == 0,
    "the pin map uses PA2 or PA3, which the firmware keeps with feature `field-update`: USART2, the field-update link on the ST-LINK's virtual COM port; wire those signals to other pins or build without the feature"
);

/// Configures the pins of the pin map: inputs with their pull resistor,
/// outputs push-pull at the level of signal 0 (the output image before
/// the first scan). With feature `field-update`, PA2 and PA3 are not
/// offered but returned for the link.
pub fn configure(ports: Ports) -> (Io, LinkPins) {
    let mut io = Io::default();
    let link;
    {
        let Ports { a, b, c, d, e, h } = ports;
        // PA13/PA14 (SWD, `MCU.reserved`) are not offered.
        #[cfg(not(feature = "field-update"))]
        {
            claim_pins!(
                io,
                a,
                [pa0, pa1, pa2, pa3, pa4, pa5, pa6, pa7, pa8, pa9, pa10, pa11, pa12, pa15]
            );
            link = ();
        }
        // Nor PA2/PA3 (USART2, the field-update link).
        #[cfg(feature = "field-update")]
        {
            claim_pins!(
                io,
                a,
                [pa0, pa1, pa4, pa5, pa6, pa7, pa8, pa9, pa10, pa11, pa12, pa15]
            );
            link = (a.pa2, a.pa3);
        }
        claim_pins!(
            io,
            b,
            [
                pb0, pb1, pb2, pb3, pb4, pb5, pb6, pb7, pb8, pb9, pb10, pb11, pb12, pb13, pb14,
                pb15
            ]
        );
        claim_pins!(
            io,
            c,
            [
                pc0, pc1, pc2, pc3, pc4, pc5, pc6, pc7, pc8, pc9, pc10, pc11, pc12, pc13, pc14,
                pc15
            ]
        );
        claim_pins!(
            io,
            d,
            [
                pd0, pd1, pd2, pd3, pd4, pd5, pd6, pd7, pd8, pd9, pd10, pd11, pd12, pd13, pd14,
                pd15
            ]
        );
        claim_pins!(
            io,
            e,
            [
                pe0, pe1, pe2, pe3, pe4, pe5, pe6, pe7, pe8, pe9, pe10, pe11, pe12, pe13, pe14,
                pe15
            ]
        );
        // PH0 (HSE input, `MCU.reserved`) is not offered.
        claim_pins!(io, h, [ph1]);
    }
    (io, link)
}

/// Claims pins for [`configure`].
trait Claim {
    /// Configures `pin` for the signal it carries, if any.
    fn claim<const P: char, const N: u8, MODE: PinMode>(&mut self, pin: gpio::Pin<P, N, MODE>);
}

impl Claim for Io {
    fn claim<const P: char, const N: u8, MODE: PinMode>(&mut self, pin: gpio::Pin<P, N, MODE>) {
        if let Some(i) = Slot::<P, N>::INPUT {
            if let Some(spec) = INPUT_PINS[i] {
                self.inputs[i] = Some(Input::new(pin, hal_pull(spec.pull)).erase());
            }
        } else if let Some(o) = Slot::<P, N>::OUTPUT {
            if let Some(spec) = OUTPUT_PINS[o] {
                let idle = match idle_state(&spec) {
                    PinState::High => gpio::PinState::High,
                    PinState::Low => gpio::PinState::Low,
                };
                self.outputs[o] = Some(Output::<PushPull>::new(pin, idle).erase());
            }
        }
    }
}

/// Makes every edge-latched input (`board::EDGE_LATCHED`) interrupt on
/// both edges of its EXTI line; the caller unmasks the lines in the
/// NVIC.
pub fn latch_edges(io: &mut Io, syscfg: &mut SysCfg, exti: &mut EXTI) {
    for (pin, latched) in io.inputs.iter_mut().zip(board::EDGE_LATCHED) {
        if let (Some(pin), true) = (pin, latched) {
            pin.make_interrupt_source(syscfg);
            pin.trigger_on_edge(exti, Edge::RisingFalling);
            pin.enable_interrupt(exti);
            pin.clear_interrupt_pending_bit();
        }
    }
}
