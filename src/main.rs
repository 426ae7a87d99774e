//! The `fair` command: see `fair --help`. The built-in methods; a program with its own is
//! the same line with its own catalogue (`examples/custom_method.rs`).

fn main() -> std::process::ExitCode {
    fair_cli::main_with(fairing::catalog::Catalog::builtin())
}
