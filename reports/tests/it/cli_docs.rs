//! `splinelab cli-docs`: the generated reference holds exactly what each
//! command's `--help` prints, and a man page per visible command.

use crate::common::{splinelab, stdout_ok, tmpdir};

/// The subcommands `splinelab --help` lists (its "Commands:" block).
fn listed_commands() -> Vec<String> {
    let help = stdout_ok(&["--help"]);
    help.lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next().map(str::to_string))
        .filter(|name| name != "help")
        .collect()
}

#[test]
fn every_listed_command_has_its_help_verbatim_and_a_man_page() {
    let dir = tmpdir("cli_docs", "all");
    let (man, md) = (dir.join("man"), dir.join("cli.md"));
    let out = splinelab(&[
        "cli-docs",
        "--man",
        man.to_str().unwrap(),
        "--markdown",
        md.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let page = std::fs::read_to_string(&md).unwrap();
    let commands = listed_commands();
    assert!(commands.len() >= 13, "{commands:?}");
    assert!(
        !commands.iter().any(|c| c == "cli-docs"),
        "the generator is hidden"
    );
    for name in &commands {
        let help = stdout_ok(&[name, "--help"]);
        assert!(
            page.contains(&format!("### `splinelab {name}`")),
            "no section for {name}"
        );
        assert!(
            page.contains(help.trim_end()),
            "the page's `{name}` section is not what `{name} --help` prints"
        );
        let roff = std::fs::read_to_string(man.join(format!("splinelab-{name}.1"))).unwrap();
        assert!(roff.contains(".TH"), "{name}: {roff:.80}");
        // roff escapes the hyphens of `bezier-eval` in the SYNOPSIS line.
        let synopsis = format!("splinelab {}", name.replace('-', "\\-"));
        assert!(roff.contains(&synopsis), "{name}: no `{synopsis}`");
        assert!(
            roff.contains(&format!("splinelab {}", env!("CARGO_PKG_VERSION"))),
            "{name}: no version in the title line"
        );
    }
    // Nested subcommands too (`check prefilter`).
    let nested = stdout_ok(&["check", "prefilter", "--help"]);
    assert!(page.contains(nested.trim_end()));
    assert!(man.join("splinelab-check-prefilter.1").is_file());
    assert!(
        !page.contains("### `splinelab cli-docs`") && !page.contains("  cli-docs "),
        "the hidden generator has no section and is not listed"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
