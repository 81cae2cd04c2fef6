# SPDX-License-Identifier: MIT
# Evaluates a Yosys Tcl script (argv 0) outside Yosys and prints the Yosys
# commands it calls, one a line, as a plain Yosys script (fpga/bin/yosys).
# `yosys -import` is a no-op here; `yosys CMD ...` and every command Tcl does
# not know are Yosys commands.
proc ys_word {w} {
    if {$w eq "" || [regexp {[\s;#]} $w]} {
        return "\"[string map {\" \\\"} $w]\""
    }
    return $w
}
proc ys_line {words} {
    set out {}
    foreach w $words { lappend out [ys_word $w] }
    puts [join $out " "]
}
rename unknown tcl_unknown
proc unknown {args} { ys_line $args }
proc yosys {args} {
    if {[lindex $args 0] eq "-import"} { return }
    ys_line $args
}
source [lindex $argv 0]
