//! The `fair` command: see `fair --help`.

fn main() -> std::process::ExitCode {
    fair_cli::run()
}
