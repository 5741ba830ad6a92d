//! The `footprint` binary: the command line of `footprint_app`, with a counting allocator so
//! that the maps' summaries state their real sizes.

#[global_allocator]
static GLOBAL: footprint::heap::CountingAlloc = footprint::heap::CountingAlloc;

fn main() {
    footprint_app::cli::main();
}
