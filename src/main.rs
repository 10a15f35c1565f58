use clap::Parser;

fn main() {
    let cli = glint::cli::Cli::parse();
    if let Err(e) = glint::cli::run(cli) {
        eprintln!("error: {e:#}");
        std::process::exit(2);
    }
}
