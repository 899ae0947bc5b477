//! Turns the PLC project into Rust: `conveyor.plc.toml` (and the model
//! files it names) in, `OUT_DIR/conveyor.rs` out, regenerated whenever one
//! of those files changes. A project error fails the build with its
//! `file:line: message`.

fn main() {
    codegen::build::Build::new("conveyor.plc.toml").generate_or_exit();

    // The board binary only (src/bin/board.rs, feature `board`): link with
    // cortex-m-rt's script, which reads `memory.x` from this directory.
    if std::env::var("CARGO_CFG_TARGET_OS").is_ok_and(|os| os == "none") {
        let dir = std::env::var("CARGO_MANIFEST_DIR").expect("set by cargo");
        println!("cargo:rustc-link-search={dir}");
        println!("cargo:rerun-if-changed=memory.x");
        println!("cargo:rustc-link-arg-bin=board=-Tlink.x");
    }
}
