//! Machine files: a TOML description of the machine (`--machine FILE`) laid over
//! the interpreter's built-in [`MachineConfig::default`]. See
//! examples/machines/default.toml for every field with its built-in value.
//!
//! Users write what the control's setting pages show: mm, mm/min, degrees, and X
//! positions (limits, reference positions, work and tool offsets) as diameters;
//! axis rates are slide speeds and are not doubled for X.

mod apply;
mod dump;
pub mod file;

use std::path::Path;

use interp_core::MachineConfig;

use crate::error::Error;
use file::MachineFile;

/// The machine described by the TOML text `text`; the error names the field. A
/// file of `kind = "mill"` starts from the built-in machining centre
/// ([`MachineConfig::mill`]: X, Y, Z in radius), any other from the built-in lathe.
pub fn parse(text: &str) -> Result<MachineConfig, String> {
    let file: MachineFile = toml::from_str(text).map_err(|e| e.to_string().trim_end().to_owned())?;
    let mut cfg = match file.kind {
        Some(file::KindName::Mill) => MachineConfig::mill(),
        _ => MachineConfig::default(),
    };
    apply::apply(&file, &mut cfg)?;
    Ok(cfg)
}

/// Reads the machine file at `path`.
pub fn load(path: &Path) -> Result<MachineConfig, Error> {
    let text = std::fs::read_to_string(path).map_err(|source| Error::Read { path: path.to_owned(), source })?;
    parse(&text).map_err(|message| Error::Machine { path: path.to_owned(), message })
}

/// The machine given with `--machine`, or the built-in one.
pub fn load_or_default(path: Option<&Path>) -> Result<MachineConfig, Error> {
    path.map_or_else(|| Ok(MachineConfig::default()), load)
}

/// `cfg` as a machine file that [`parse`] reads back to the same configuration.
pub fn to_toml(cfg: &MachineConfig) -> Result<String, toml::ser::Error> {
    toml::to_string(&dump::file_of(cfg))
}
