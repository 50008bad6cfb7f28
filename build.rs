//! Link flags of the FMU binary.

fn main() {
    // Keep the shared library mapped after dlclose: the Rust runtime registers thread-local
    // destructors that must not outlive the code (importers load and unload FMUs freely).
    println!("cargo:rustc-cdylib-link-arg=-Wl,-z,nodelete");
    println!("cargo:rerun-if-changed=build.rs");
}
