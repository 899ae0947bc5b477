//! `codegen image`: a project's program image (configuration and tables,
//! table backend) as a slot file for a field update
//! (docs/field-update.md): what `codegen load` sends and what a debug
//! probe writes into a slot.

use super::error::CliError;
use super::output::Out;
use super::progress::load_project;
use super::Outcome;
use codegen::backend::Backend;
use codegen::lower::Lowered;
use executor::program::Program;
use executor::table::SupervisorTable;
use field_update::header::version_parts;
use field_update::host::SlotFile;
use field_update::CRC_ALGORITHM;
use std::path::PathBuf;

/// The CRC of slot headers and images.
static CRC: crc::Crc<u32> = crc::Crc::<u32>::new(&CRC_ALGORITHM);

/// `codegen image` arguments.
#[derive(Debug, clap::Args)]
pub struct ImageArgs {
    /// The project file (`*.plc.toml`).
    project: PathBuf,
    /// The slot file to write.
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
    /// The program's version the slot header records (`MAJOR.MINOR.PATCH`).
    #[arg(long, default_value = "0.0.0", value_parser = parse_version)]
    version: u32,
    /// The sequence number the slot header records: a debug probe writes
    /// it as it is (give one above the other slot's); a load over the
    /// serial link replaces it with the running slot's plus one.
    #[arg(long, default_value_t = 1)]
    sequence: u32,
}

/// `MAJOR.MINOR.PATCH` (major below 65,536, the others below 256).
fn parse_version(text: &str) -> Result<u32, String> {
    let parts: Vec<&str> = text.split('.').collect();
    let [major, minor, patch] = parts[..] else {
        return Err(format!("`{text}` is not MAJOR.MINOR.PATCH"));
    };
    let field = |s: &str, max: u32| {
        s.parse::<u32>()
            .ok()
            .filter(|&v| v <= max)
            .ok_or_else(|| format!("`{s}` in `{text}` is not a number from 0 to {max}"))
    };
    Ok(field(major, 0xFFFF)? << 16 | field(minor, 0xFF)? << 8 | field(patch, 0xFF)?)
}

pub fn run(args: &ImageArgs, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    let (project, spinner) = load_project(&args.project)?;
    spinner.phase("generating");
    let lowered = Lowered::new(&project, Backend::Table, &spinner)?;
    drop(spinner);
    let words = executor::image::words(&lowered);
    let crc = lowered.recorded_crc();
    // What the PLC will check, checked here first: a refusal is a bug of
    // the generator, not of the project.
    let wiring = codegen::board::wiring_signature(&project);
    let file = SlotFile::new(words, args.sequence, args.version, wiring, &CRC);
    if file.header.image_crc != crc {
        return Err(CliError::Usage(format!(
            "{}: the image's words do not give its recorded CRC (a generator bug)",
            args.project.display()
        )));
    }
    let mut name = vec![0u8; file.image.len() * 4];
    let mut tables = vec![SupervisorTable::EMPTY; lowered.config().supervisors.len()];
    if let Err(refusal) = executor::parse::load(&file.image, &mut name, &mut tables, crc) {
        return Err(CliError::Usage(format!(
            "{}: the image read back is refused ({refusal}; a generator bug)",
            args.project.display()
        )));
    }
    let bytes = file.to_bytes(&CRC);
    std::fs::write(&args.output, &bytes).map_err(|e| des::Error::io(&args.output, e))?;
    let (major, minor, patch) = version_parts(args.version);
    if json {
        out.json(&serde_json::json!({
            "project": project.name,
            "words": file.image.len(),
            "image_crc": format!("{crc:#010x}"),
            "version": format!("{major}.{minor}.{patch}"),
            "sequence": args.sequence,
            "wiring": format!("{wiring:#010x}"),
            "file": args.output.display().to_string(),
            "file_bytes": bytes.len(),
        }));
    } else {
        out.line(format_args!(
            "{}: image of {} words ({} B), CRC {crc:#010x}, version {major}.{minor}.{patch}, sequence {}, wiring {wiring:#010x} -> {} ({} B)",
            project.name,
            file.image.len(),
            file.image.len() * 4,
            args.sequence,
            args.output.display(),
            bytes.len()
        ));
    }
    Ok(Outcome::Holds)
}
