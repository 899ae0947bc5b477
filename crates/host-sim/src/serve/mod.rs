//! `host-sim serve`: any project in the browser, in closed loop with a
//! simulated machine (docs/simulator.md).
//!
//! A local HTTP server holds one [`Session`] and serves a page (three
//! files in `page/`, compiled in) that shows and steers it through a JSON
//! API. The simulation runs here, natively, in the same code as `host-sim
//! replay`: the page only draws, so what it shows is what the executor
//! did, and a run saved as `inputs.csv` replays to the same trace.
//!
//! - [`session`]: the simulation, its log, plots and files;
//! - [`machine`]: what simulates the machine (plant automata, the boiler's
//!   or the cell's physics, or nothing);
//! - [`stimulus`]: the input changes that make an uncontrollable event;
//! - [`explain`]: which supervisor disables a command, and why;
//! - [`history`]: the plots' samples;
//! - [`json`]: what the API sends;
//! - [`http`]: the routes.

pub mod explain;
pub mod history;
pub mod http;
pub mod json;
pub mod machine;
pub mod session;
pub mod stimulus;

pub use machine::PlantChoice;
pub use session::Session;
