#!/usr/bin/env python3
# Import circles between the modules of each crate given (its src folder): an edge for every
# path naming crate::a::b or super::x, resolved to the module that holds it. A module naming
# one of its own ancestors is no edge (the ancestor declares it and may re-export it), so what
# is reported are circles between siblings or cousins. Exits non-zero when there is one.
#   tools/import-circles.py crates/*/src
# It also holds the rooms of a folder to their order (ROOMS below): a room may read the rooms
# before it in its list, never one after it (no import back up). Test files count too.
import os,re,sys
def modules(src):
    mods={}
    for root,_,files in os.walk(src):
        for f in files:
            if not f.endswith('.rs'): continue
            p=os.path.join(root,f); rel=os.path.relpath(p,src)[:-3].split(os.sep)
            if rel[-1] in ('mod','lib','main'): rel=rel[:-1]
            mods[tuple(rel)]=p
    return mods
def resolve(path, mods):
    # longest prefix that is a module
    for k in range(len(path),-1,-1):
        if tuple(path[:k]) in mods: return tuple(path[:k])
    return ()
def edges(mods):
    E={m:set() for m in mods}
    for m,p in mods.items():
        text=open(p).read()
        text=re.sub(r'(?s)#\[cfg\(test\)\]\s*mod tests \{.*','',text)
        for mt in re.finditer(r'\b(crate|super)((?:::\w+)+)', text):
            parts=mt.group(2).split('::')[1:]
            if mt.group(1)=='crate': base=[]
            else:
                base=list(m[:-1]) if not p.endswith(('mod.rs','lib.rs','main.rs')) else list(m[:-1])
                # `super` inside a file module means the parent module
            # handle `super::super`
            while parts and parts[0]=='super': base=base[:-1]; parts=parts[1:]
            t=resolve(base+parts,mods)
            if t==m or m[:len(t)]==t: continue  # self or ancestor
            E[m].add(t)
        # `use a::b` where a is a child module declared here
    return E
def sccs(E):
    index={};low={};st=[];on=set();out=[];i=[0]
    sys.setrecursionlimit(10000)
    def sc(v):
        index[v]=low[v]=i[0];i[0]+=1;st.append(v);on.add(v)
        for w in E.get(v,()):
            if w not in index: sc(w);low[v]=min(low[v],low[w])
            elif w in on: low[v]=min(low[v],index[w])
        if low[v]==index[v]:
            comp=[]
            while True:
                w=st.pop();on.discard(w);comp.append(w)
                if w==v:break
            if len(comp)>1: out.append(comp)
    for v in E:
        if v not in index: sc(v)
    return out
# Each folder's rooms, lowest first (ARCHITECTURE.md draws them).
ROOMS={
    'crates/sylva/src': [
        ('street', ['error','site','energy','work','accounts','study','rank','records','picture']),
        ('growth', ['error','data','model','survey','season']),
    ],
    'crates/sylva-city/src': [
        ('', ['error','geo','inventory','demo','trees','tiles','report','tasks','cache','run','bench']),
    ],
}
def backwards(crate, E):
    out=[]
    for parent,order in ROOMS.get(os.path.normpath(crate),[]):
        pre=tuple(parent.split('::')) if parent else ()
        def room(m):
            if m[:len(pre)]!=pre or len(m)<=len(pre) or m[len(pre)] not in order: return None
            return order.index(m[len(pre)])
        for m,ts in E.items():
            for t in ts:
                a,b=room(m),room(t)
                if a is not None and b is not None and b>a: out.append((m,t))
    return out
bad=0; up=0
for crate in sys.argv[1:]:
    mods=modules(crate)
    E=edges(mods)
    for comp in sccs(E):
        bad+=1; print(crate, 'circle:', sorted('::'.join(c) or 'lib' for c in comp))
    for m,t in backwards(crate, E):
        up+=1; print(crate, 'import back up:', '::'.join(m), '->', '::'.join(t))
print('import circles:',bad, ' imports back up:', up)
sys.exit(1 if bad or up else 0)
