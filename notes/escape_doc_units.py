#!/usr/bin/env python3
# Escapes unit brackets in doc comments (`[N]` -> `\\[N\\]`) so rustdoc does not read them as
# intra-doc links. Usage: python3 notes/escape_doc_units.py FILE.rs ... (edits in place).
# Not for clap argument docs (clap would print the backslashes in --help).
import re,sys
pat=re.compile(r'(?<!\\)\[(m|N|s|J|Pa|rad|dimensionless|ns|kg|deg|W|Hz|ms|mm|um|K)\](?![\(\[])')
for f in sys.argv[1:]:
    lines=open(f).read().split('\n')
    out=[];n=0
    for l in lines:
        st=l.lstrip()
        if st.startswith('///') or st.startswith('//!'):
            l2=pat.sub(lambda m: '\\['+m.group(1)+'\\]', l)
            n+= l2!=l
            l=l2
        out.append(l)
    if n:
        open(f,'w').write('\n'.join(out)); print(f,n)
