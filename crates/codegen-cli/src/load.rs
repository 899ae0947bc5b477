//! `codegen load`: a slot file (`codegen image`) into a running PLC over
//! a serial port, with the field-update protocol (`field_update`,
//! docs/field-update.md); without a file, what the PLC runs.

use super::error::CliError;
use super::output::{warn, Out};
use super::Outcome;
use field_update::header::version_parts;
use field_update::host::{load, Link, SlotFile, DEFAULT_TIMEOUT_MS};
use field_update::protocol::{Request, Response, Status};
use field_update::CRC_ALGORITHM;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::Duration;

/// The CRC of frames, slot headers and images.
static CRC: crc::Crc<u32> = crc::Crc::<u32>::new(&CRC_ALGORITHM);

/// `codegen load` arguments.
#[derive(Debug, clap::Args)]
pub struct LoadArgs {
    /// The slot file to load (`codegen image`); without it, only ask the
    /// PLC what it runs.
    file: Option<PathBuf>,
    /// The PLC's serial port (`/dev/ttyACM0`, `COM3`, …).
    #[arg(long)]
    port: String,
    /// Baud rate of the port.
    #[arg(long, default_value_t = 115_200)]
    baud: u32,
    /// Milliseconds to wait for an answer before sending a request again
    /// (three tries); `Begin`'s answer, which comes after the PLC erased
    /// a slot, is waited for up to 4 s longer.
    #[arg(long, default_value_t = DEFAULT_TIMEOUT_MS)]
    timeout_ms: u64,
}

pub fn run(args: &LoadArgs, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    let file = match &args.file {
        Some(path) => {
            let bytes = std::fs::read(path)
                .map_err(|e| CliError::Usage(format!("{}: {e}", path.display())))?;
            let file = SlotFile::parse(&bytes, &CRC).map_err(|e| {
                CliError::Usage(format!("{}: not a slot file: {e}", path.display()))
            })?;
            Some(file)
        }
        None => None,
    };
    let port = serialport::new(&args.port, args.baud)
        .timeout(Duration::from_millis(args.timeout_ms))
        .open()
        .map_err(|e| CliError::Usage(format!("{}: {e}", args.port)))?;
    let mut link = Link::new(port, &CRC).timeout_ms(args.timeout_ms);
    let before = status(&mut link)?;
    let mut report = serde_json::json!({ "before": before.0 });
    if !json {
        out.line(format_args!("before: {}", before.1));
    }
    if let Some(file) = &file {
        let bar = bar(file.image.len() as u64 * 4);
        let loaded = load(&mut link, file, |sent, _| bar.set_position(u64::from(sent)))?;
        bar.finish_and_clear();
        let after = status(&mut link)?;
        if json {
            report["loaded"] = serde_json::json!({
                "slot": format!("{:?}", loaded.slot),
                "sequence": loaded.sequence,
            });
            report["after"] = after.0;
        } else {
            out.line(format_args!(
                "loaded {} words into slot {:?} (sequence {}): it runs from the next scan",
                file.image.len(),
                loaded.slot,
                loaded.sequence
            ));
            out.line(format_args!("after: {}", after.1));
        }
    }
    if json {
        out.json(&report);
    }
    Ok(Outcome::Holds)
}

/// The PLC's status as JSON and as a line of text.
fn status<T: std::io::Read + std::io::Write>(
    link: &mut Link<'_, T>,
) -> Result<(serde_json::Value, String), CliError> {
    match link.request(&Request::Status)? {
        Response::Status(s) => Ok((status_json(&s), status_line(&s))),
        other => {
            warn(format_args!(
                "warning: unexpected answer to Status: {other:?}"
            ));
            Err(CliError::Usage(
                "the PLC did not answer Status with its status".into(),
            ))
        }
    }
}

fn status_json(s: &Status<'_>) -> serde_json::Value {
    serde_json::json!({
        "project": s.name,
        "slot": s.slot.map(|slot| format!("{slot:?}")),
        "version": version_text(s.version),
        "image_crc": format!("{:#010x}", s.image_crc),
        "wiring": format!("{:#010x}", s.wiring),
        "loading": s.loading,
    })
}

fn status_line(s: &Status<'_>) -> String {
    let from = match s.slot {
        Some(slot) => format!("slot {slot:?}, version {}", version_text(s.version)),
        None => "the program built into the firmware".to_owned(),
    };
    let loading = match s.loading {
        Some(offset) => format!("; a load stands at byte {offset}"),
        None => String::new(),
    };
    format!(
        "`{}` runs from {from}, image CRC {:#010x}, wiring {:#010x}{loading}",
        s.name, s.image_crc, s.wiring
    )
}

fn version_text(version: u32) -> String {
    let (major, minor, patch) = version_parts(version);
    format!("{major}.{minor}.{patch}")
}

/// A byte progress bar on stderr, hidden when stderr is not a terminal.
fn bar(total: u64) -> ProgressBar {
    if !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("loading {bar:40} {bytes}/{total_bytes}")
            .expect("valid template"),
    );
    bar
}
