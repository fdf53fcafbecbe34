# Every ```c block of the pages given, as a function body to compile (make test): a fragment uses
# names it does not declare, so the HTML comment on the line before it,
#     <!-- compiled with: hb_plan *plan; float *theta_o; -->
# declares them, each as a static local (zero: the compiler only checks the calls against hairbsdf.h).
BEGIN {
    print "#include <stddef.h>"
    print "#include <stdio.h>"
    print "#include \"hairbsdf.h\""
}
FNR == 1 { before = "" }
/^```c$/ {
    on = 1
    blocks++
    printf "void hb_docs_block_%d(void); /* %s:%d */\nvoid hb_docs_block_%d(void)\n{\n", blocks, FILENAME, FNR, blocks
    if (before ~ /^<!-- compiled with: .* -->$/) {
        decls = before
        sub(/^<!-- compiled with: /, "", decls)
        sub(/ -->$/, "", decls)
        count = split(decls, declaration, ";")
        for (k = 1; k <= count; k++)
            if (declaration[k] ~ /[^ ]/)
                print "static " declaration[k] ";"

    }
    next
}
on && /^```$/ { on = 0; print "}"; next }
on { print; next }
{ before = $0 }
END { if (!blocks) { print "no ```c block in the pages" > "/dev/stderr"; exit 1 } }
