//! Parser and syntax tree for SINUMERIK part programs.
//!
//! Parsing never fails: [`parse`] always returns a [`Program`](ast::Program) together with
//! the diagnostics found on the way. A malformed block yields one diagnostic
//! and parsing resumes at the next block; an unclosed control structure
//! names both its opener and where its end was expected.
//!
//! ```
//! use gcodec_source::SourceFile;
//! let file = SourceFile::new("demo.mpf", "N10 G1 X=R1+5 F200 ; cut\nM30\n");
//! let parsed = gcodec_parser::parse(&file);
//! assert!(parsed.diagnostics.is_empty());
//! assert_eq!(parsed.program.blocks[0].statements.len(), 3);
//! ```

pub mod ast;
mod driver;
mod error;
mod fast;
mod grammar;
mod macros;
mod misspelt;
mod plain_glance;
mod structure;
mod tree;
mod word_line;

pub use driver::{
    MAX_EXPRESSION_DEPTH, MAX_OPERATORS_PER_BLOCK, Parse, ParsedChunk, lines_of, parse,
    parse_bytes, parse_bytes_in_chunks, parse_bytes_with_grammar_only, parse_chunk,
    parse_chunk_of_lexed_lines, parse_with_macros, plain_lines_skimmable_after, skim_chunk,
    skim_chunks,
};
pub use macros::{MAX_EXPANDED_BYTES, MAX_MACRO_DEPTH, Macro, Macros};
pub use structure::Pairing;
pub use tree::{write_expr, write_tree};
pub use word_line::{ConstantWord, WordLine};
