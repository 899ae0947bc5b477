//! `codegen convert`: between model formats.

use super::error::CliError;
use super::output::{outln, Out};
use super::{load_components, Outcome};
use des::formats::{self, Kind};
use std::path::PathBuf;

/// Arguments of `codegen convert`.
#[derive(Debug, clap::Args)]
pub struct ConvertArgs {
    /// Input file.
    input: PathBuf,
    /// Output file; its extension picks the format.
    output: PathBuf,
    /// Only this component (for files holding several).
    #[arg(long)]
    component: Option<String>,
    /// Give the written components this kind. By default each keeps the
    /// kind its file states; one that states none (libFAUDES or TCT files
    /// from elsewhere) stays unstated, which a `.wmod` must write as PLANT.
    #[arg(long, value_enum)]
    kind: Option<KindArg>,
}

#[derive(Debug, Clone, Copy, clap::ValueEnum)]
enum KindArg {
    Plant,
    Spec,
    Supervisor,
    Property,
}

impl From<KindArg> for Kind {
    fn from(k: KindArg) -> Kind {
        match k {
            KindArg::Plant => Kind::Plant,
            KindArg::Spec => Kind::Spec,
            KindArg::Supervisor => Kind::Supervisor,
            KindArg::Property => Kind::Property,
        }
    }
}

pub fn run(args: &ConvertArgs, json: bool, out: &mut Out) -> Result<Outcome, CliError> {
    let mut components = load_components(&args.input, args.component.as_deref())?;
    if let Some(kind) = args.kind {
        for c in &mut components {
            c.kind = kind.into();
        }
    }
    formats::write_file(&args.output, &components)?;
    if json {
        let written: Vec<_> = components
            .iter()
            .map(|c| serde_json::json!({ "name": c.automaton.name(), "kind": c.kind }))
            .collect();
        out.json(&serde_json::json!({
            "input": args.input.display().to_string(),
            "output": args.output.display().to_string(),
            "components": written,
        }));
    } else {
        let written: Vec<String> = components
            .iter()
            .map(|c| format!("{} ({})", c.automaton.name(), c.kind))
            .collect();
        outln!(
            out,
            "wrote {}: {}",
            args.output.display(),
            written.join(", ")
        );
    }
    Ok(Outcome::Holds)
}
