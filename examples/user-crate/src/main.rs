fn main() -> std::process::ExitCode {
    fair_cli::main_with(laplacian_fair::catalog())
}
