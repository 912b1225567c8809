//! `index.html`: one page per `compare` or `sweep` folder that shows its figures, images and
//! tables and links its data files, so a whole comparison can be looked at in a browser.
//! Plain HTML and CSS with relative links (the folder can be moved or served as it is); a
//! few lines of script count the images that did not load and say so at the top of the page
//! (and in the `data-broken-images` attribute of `<body>`, which the tests read through
//! headless Chromium, as they read `data-wide-tables`: the tables wider than the window).
//! Table headers wrap at their underscores, so a wide table fits a 1400-pixel window; where
//! one does not fit, its first column (the strategy) stays in view while it scrolls.
use crate::figure::xml_escape;
use crate::table::TextTable;
use slc_app::out_dir::OutDir;
use slc_app::provenance::Provenance;
use std::fmt::Write;

/// One part of the page, in order.
pub enum Block {
    Heading(String),
    /// A figure across the page: a file of the folder and its caption; `pdf` names the same
    /// figure as PDF where one was written.
    Figure {
        src: String,
        caption: String,
        pdf: Option<String>,
    },
    /// Images side by side, each with a caption.
    Gallery(Vec<(String, String)>),
    Table(TextTable),
    /// Links to files of the folder.
    Links(Vec<String>),
}

impl Block {
    /// The figure `{stem}.svg` of `out` with `caption`, and its PDF where `out` has one.
    pub fn figure(out: &OutDir, stem: &str, caption: &str) -> Self {
        let pdf = format!("{stem}.pdf");
        Block::Figure {
            src: format!("{stem}.svg"),
            pdf: out.has(&pdf).then_some(pdf),
            caption: caption.into(),
        }
    }
}

/// A page of blocks under a title, with the run's provenance at its foot.
pub struct Page<'a> {
    pub title: String,
    pub provenance: &'a Provenance,
    pub blocks: Vec<Block>,
}

const STYLE: &str = "body{font-family:sans-serif;margin:1.5em auto;max-width:1500px;padding:0 1em;color:#222}\
h1{font-size:1.5em}h2{font-size:1.2em;margin-top:1.6em;border-bottom:1px solid #ccc}\
figure{margin:.8em 0}figure img{max-width:100%;border:1px solid #ddd}figcaption{font-size:.9em;color:#555}\
.gallery{display:flex;flex-wrap:wrap;gap:.8em}.gallery figure{margin:0;flex:0 0 calc(25% - .6em)}\
.gallery img{image-rendering:pixelated;width:100%}.scroll{overflow-x:auto}\
table{border-collapse:collapse;font-size:.85em}td,th{border:1px solid #ccc;padding:.2em .5em;text-align:right}\
th{background:#f2f2f2;vertical-align:bottom;max-width:7em}td:first-child,th:first-child{text-align:left}\
td:first-child,th:first-child{position:sticky;left:0;z-index:1;box-shadow:1px 0 0 #ccc}td:first-child{background:#fff}\
#broken{display:none;background:#fdd;padding:.5em;border:1px solid #c00}\
.provenance{font-size:.8em;color:#555}code{font-size:.95em}";

/// Counts images that failed to load, shows the count and records it on `<body>`.
const SCRIPT: &str = "window.addEventListener('load',function(){\
var bad=[].filter.call(document.images,function(i){return !(i.complete&&i.naturalWidth>0);});\
document.body.setAttribute('data-broken-images',String(bad.length));\
document.body.setAttribute('data-images',String(document.images.length));\
var wide=[].filter.call(document.querySelectorAll('.scroll'),function(d){return d.scrollWidth>d.clientWidth+1;});\
document.body.setAttribute('data-wide-tables',String(wide.length));\
if(bad.length){var b=document.getElementById('broken');b.style.display='block';\
b.textContent=bad.length+' image(s) did not load: '+bad.map(function(i){return i.getAttribute('src');}).join(', ');}});";

fn table_html(t: &TextTable, html: &mut String) {
    html.push_str("<div class=\"scroll\"><table><tr>");
    for h in &t.header {
        // Long column names break after their underscores.
        let _ = write!(html, "<th>{}</th>", xml_escape(h).replace('_', "_<wbr>"));
    }
    html.push_str("</tr>\n");
    for row in &t.rows {
        html.push_str("<tr>");
        for cell in row {
            let _ = write!(html, "<td>{}</td>", xml_escape(cell));
        }
        html.push_str("</tr>\n");
    }
    html.push_str("</table></div>\n");
}

impl<'a> Page<'a> {
    /// The page of a command with a table: `figures`, the table `name` with links to
    /// `name.csv`, `name.json` and `notes`, `more`, then the settings every row shares.
    pub fn of_table(
        title: String,
        provenance: &'a Provenance,
        figures: Vec<Block>,
        (name, notes): (&str, &str),
        (table, settings): (TextTable, TextTable),
        more: Vec<Block>,
    ) -> Self {
        let mut blocks = figures;
        blocks.extend([
            Block::Heading("Table".into()),
            Block::Table(table),
            Block::Links(vec![
                format!("{name}.csv"),
                format!("{name}.json"),
                notes.to_string(),
            ]),
        ]);
        blocks.extend(more);
        blocks.extend([Block::Heading("Settings".into()), Block::Table(settings)]);
        Self {
            title,
            provenance,
            blocks,
        }
    }

    /// The page as HTML. Every `src` and link is relative to the folder.
    pub fn html(&self) -> String {
        let mut html = format!(
            "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{}</title>\
             <style>{STYLE}</style><script>{SCRIPT}</script></head>\n<body>\n<h1>{}</h1>\n\
             <div id=\"broken\"></div>\n",
            xml_escape(&self.title),
            xml_escape(&self.title)
        );
        for block in &self.blocks {
            match block {
                Block::Heading(h) => {
                    let _ = writeln!(html, "<h2>{}</h2>", xml_escape(h));
                }
                Block::Figure { src, caption, pdf } => {
                    let pdf = pdf.as_ref().map_or_else(String::new, |p| {
                        format!(" (<a href=\"{0}\">PDF</a>)", xml_escape(p))
                    });
                    let _ = writeln!(
                        html,
                        "<figure><a href=\"{0}\"><img src=\"{0}\" alt=\"{1}\"></a><figcaption>{1}{pdf}</figcaption></figure>",
                        xml_escape(src),
                        xml_escape(caption)
                    );
                }
                Block::Gallery(items) => {
                    html.push_str("<div class=\"gallery\">\n");
                    for (src, caption) in items {
                        let _ = writeln!(
                            html,
                            "<figure><a href=\"{0}\"><img src=\"{0}\" alt=\"{1}\"></a><figcaption>{1}</figcaption></figure>",
                            xml_escape(src),
                            xml_escape(caption)
                        );
                    }
                    html.push_str("</div>\n");
                }
                Block::Table(t) => table_html(t, &mut html),
                Block::Links(files) => {
                    html.push_str("<p>Data: ");
                    let links: Vec<String> = files
                        .iter()
                        .map(|f| format!("<a href=\"{0}\"><code>{0}</code></a>", xml_escape(f)))
                        .collect();
                    html.push_str(&links.join(" · "));
                    html.push_str("</p>\n");
                }
            }
        }
        let p = self.provenance;
        let _ = writeln!(
            html,
            "<h2>Provenance</h2>\n<p class=\"provenance\">slc {} ({}), built by {} ({}), started {} on {} ({} threads), {}.<br>\
             Command: <code>{}</code><br>Scene (SHA-256 of its whole description) <code>{}</code>; files: {}</p>\n</body></html>",
            p.slc_version,
            xml_escape(p.git_commit.unwrap_or("not built from git")),
            xml_escape(p.rustc),
            xml_escape(p.build_profile),
            xml_escape(&p.started_at),
            xml_escape(p.cpu.as_deref().unwrap_or("an unknown CPU")),
            p.cpu_threads,
            xml_escape(&p.os),
            xml_escape(&p.command_line.join(" ")),
            p.scene_sha256,
            if p.scene_files.is_empty() {
                "none (a built-in scene)".to_string()
            } else {
                p.scene_files
                    .iter()
                    .map(|f| {
                        format!(
                            "<code>{}</code> (SHA-256 {})",
                            xml_escape(&f.path),
                            f.sha256.as_deref().unwrap_or("unreadable")
                        )
                    })
                    .collect::<Vec<_>>()
                    .join(", ")
            }
        );
        html
    }

    /// Stages `index.html` in `out`, after checking that every file the page shows or links is
    /// staged there too.
    pub fn write(&self, out: &mut OutDir) -> Result<(), String> {
        let referenced = self.blocks.iter().flat_map(|b| match b {
            Block::Figure { src, pdf, .. } => std::iter::once(src.as_str())
                .chain(pdf.as_deref())
                .collect(),
            Block::Gallery(items) => items.iter().map(|(s, _)| s.as_str()).collect(),
            Block::Links(files) => files.iter().map(String::as_str).collect(),
            _ => Vec::new(),
        });
        for f in referenced {
            if !out.has(f) {
                return Err(format!(
                    "index.html would show {f}, which this run did not write (a bug in slc)"
                ));
            }
        }
        out.write("index.html", self.html().as_bytes())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn provenance() -> Provenance {
        Provenance {
            // Other tests of this process may have hashed a scene file first.
            scene_files: Vec::new(),
            ..Provenance::new(&slc_core::builtin("default").unwrap())
        }
    }

    #[test]
    fn the_page_shows_every_block_escaped() {
        let p = provenance();
        let page = Page {
            title: "compare <cornell>".into(),
            provenance: &p,
            blocks: vec![
                Block::Heading("Table".into()),
                Block::Table(TextTable {
                    header: vec!["strategy".into(), "ms".into()],
                    rows: vec![vec!["a&b".into(), "1.5".into()]],
                }),
                Block::Figure {
                    src: "side_by_side.svg".into(),
                    caption: "panels".into(),
                    pdf: Some("side_by_side.pdf".into()),
                },
                Block::Gallery(vec![("x/total.png".into(), "total".into())]),
                Block::Links(vec!["compare.csv".into()]),
            ],
        };
        let html = page.html();
        assert!(html.starts_with("<!DOCTYPE html>") && html.trim_end().ends_with("</html>"));
        assert!(html.contains("<title>compare &lt;cornell&gt;</title>"));
        assert!(html.contains("<td>a&amp;b</td>"));
        assert_eq!(html.matches("<img ").count(), 2);
        assert!(html.contains("(<a href=\"side_by_side.pdf\">PDF</a>)"));
        assert!(html.contains("href=\"compare.csv\""));
        assert!(html.contains("a built-in scene"));
    }

    #[test]
    fn a_page_that_shows_a_file_the_run_did_not_write_is_refused() {
        let dir = std::env::temp_dir().join(format!("slc-page-test-{}", std::process::id()));
        let mut out = OutDir::open(&dir).unwrap();
        out.write("a.png", b"x").unwrap();
        let p = provenance();
        let page = |src: &str| Page {
            title: "t".into(),
            provenance: &p,
            blocks: vec![Block::Gallery(vec![(src.into(), "c".into())])],
        };
        assert!(page("a.png").write(&mut out).is_ok());
        let e = page("b.png").write(&mut out).unwrap_err();
        assert!(e.contains("b.png"), "{e}");
        drop(out);
        let _ = std::fs::remove_dir_all(dir);
    }
}
