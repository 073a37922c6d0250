#include "engine/report/instance_player_script.h"

namespace motif {

const char kInstancePlayerScript[] = R"js(
(function(){
var fe=document.getElementById('play-figure');if(!fe)return;
var F=JSON.parse(fe.textContent),NP=F.sides.length,COL=F.colours,players={};
window.motifPlayers=players;
function decode(b){var s=atob(b),n=s.length>>1,a=new Int16Array(n);
for(var i=0;i<n;i++){var v=s.charCodeAt(2*i)|(s.charCodeAt(2*i+1)<<8);a[i]=v>32767?v-65536:v;}return a;}
function el(tag,cls,html){var e=document.createElement(tag);if(cls)e.className=cls;if(html!=null)e.innerHTML=html;return e;}
function Player(box,id,data){
var P=this,I=data.instances,t=0,sel=0,playing=false,speed=1,keep=false,yaw=-0.7,pitch=0.3,last=0,A=[];
for(var i=0;i<I.length;i++)A.push(null);
function pts(i){if(!A[i])A[i]=decode(I[i].points);return A[i];}
// t: the motif's time, 0..1 over the first instance's samples; align[r]: instance i's sample
// shown with the first instance's sample r (dynamic time warping, instance_alignment.h).
var NR=I[0].samples;function refOf(){return NR>1?Math.round(t*(NR-1)):0;}
function sampleOf(i){var a=I[i].align;if(a&&a.length==NR)return a[refOf()];var n=I[i].samples;return n>1?Math.round(t*(n-1)):0;}
function timeOfSample(i,k){var a=I[i].align;if(a&&a.length==NR){for(var r=0;r<NR;r++)if(a[r]>=k)return NR>1?r/(NR-1):0;return 1;}
var n=I[i].samples;return n>1?k/(n-1):0;}
function frameOf(i){return I[i].start+sampleOf(i)*F.step;}
// point p of instance i at its current sample: relative to the first root on the ground, heading
// kept or removed; world adds the origin back (heading kept).
function point(i,p,world){var a=pts(i),k=sampleOf(i),o=(k*NP+p)*3,s=I[i].scale,x=a[o]/s,y=a[o+1]/s,z=a[o+2]/s;
if(world)return[x+I[i].origin[0],y+I[i].origin[1],z+I[i].origin[2]];
if(!keep){var h=-I[i].heading,c=Math.cos(h),d=Math.sin(h),x2=c*x+d*z;z=-d*x+c*z;x=x2;}return[x,y,z];}
function project(q,f,cv){var s=cv.height*0.8/F.height,x=q[0]-f[0],z=q[2]-f[2],cy=Math.cos(yaw),sy=Math.sin(yaw),
x1=cy*x-sy*z,z1=sy*x+cy*z,y2=Math.cos(pitch)*q[1]-Math.sin(pitch)*z1;return[cv.width/2+s*x1,cv.height*0.86-s*y2];}
function draw(cv,i,big){var g=cv.getContext('2d'),W=cv.width,H=cv.height;g.fillStyle='#fff';g.fillRect(0,0,W,H);
var Q=[];for(var p=0;p<NP;p++)Q.push(point(i,p,false));var f=[Q[F.root][0],0,Q[F.root][2]];
var step=F.height/2,R=2.5*F.height;g.strokeStyle='#ddd';g.lineWidth=1;g.beginPath();
var x0=Math.floor((f[0]-R)/step)*step,z0=Math.floor((f[2]-R)/step)*step;
for(var gx=x0;gx<=f[0]+R;gx+=step){var a=project([gx,0,f[2]-R],f,cv),b=project([gx,0,f[2]+R],f,cv);g.moveTo(a[0],a[1]);g.lineTo(b[0],b[1]);}
for(var gz=z0;gz<=f[2]+R;gz+=step){var a2=project([f[0]-R,0,gz],f,cv),b2=project([f[0]+R,0,gz],f,cv);g.moveTo(a2[0],a2[1]);g.lineTo(b2[0],b2[1]);}
g.stroke();var S=[];for(p=0;p<NP;p++)S.push(project(Q[p],f,cv));
g.lineCap='round';g.lineWidth=big?3:1.6;
for(var c=0;c<F.chains.length;c++){var ch=F.chains[c];for(var j=1;j<ch.length;j++){
g.strokeStyle=COL[F.sides[ch[j]]];g.beginPath();g.moveTo(S[ch[j-1]][0],S[ch[j-1]][1]);g.lineTo(S[ch[j]][0],S[ch[j]][1]);g.stroke();}}
if(big)P.drawn=S;}
var ui=el('div','player'),bar=el('div','pbar');
var pp=el('button','pp','&#9654; play'),scrub=el('input','scrub'),lab=el('span','pframe'),
sp=el('select','speed','<option value="0.25">0.25&times;</option><option value="0.5">0.5&times;</option><option value="1" selected>1&times;</option><option value="2">2&times;</option>'),
hd=el('label','heading','<input type="checkbox"> keep heading'),is=el('select','inst');
pp.type='button';scrub.type='range';scrub.min=0;scrub.step=1;
// Clip names are text, never markup.
for(i=0;i<I.length;i++){var o=el('option');o.textContent=(i+1)+': '+I[i].clip+' ['+I[i].start+', '+I[i].end+')';o.value=i;is.appendChild(o);}
bar.appendChild(pp);bar.appendChild(scrub);bar.appendChild(lab);bar.appendChild(sp);bar.appendChild(hd);bar.appendChild(is);
bar.appendChild(el('span','plegend','<b style="color:'+COL[1]+'">left</b> / <b style="color:'+COL[2]+'">right</b> limbs; drag the view to turn it'));
var main=el('canvas','pmain'),cmd=el('code','pcmd'),row=el('div','psmall'),smalls=[];main.width=480;main.height=360;
for(i=0;i<I.length;i++){var cell=el('div','pcell'),cv=el('canvas');cv.width=120;cv.height=150;cell.appendChild(cv);cell.appendChild(el('div','pcap'));
(function(k){cell.onclick=function(){P.select(k);};})(i);row.appendChild(cell);smalls.push(cell);}
ui.appendChild(bar);ui.appendChild(main);ui.appendChild(cmd);ui.appendChild(row);box.appendChild(ui);
function render(){var n=I[sel].samples;scrub.max=Math.max(0,n-1);scrub.value=sampleOf(sel);
var ff=frameOf(sel),file=I[sel].file_first+Math.round(ff*I[sel].file_rate);
lab.textContent='instance '+(sel+1)+' of '+I.length+' \u00b7 '+I[sel].clip+' \u00b7 clip frame '+ff+' (source file frame '+file+')';
draw(main,sel,true);for(var k=0;k<I.length;k++){draw(smalls[k].firstChild,k,false);smalls[k].lastChild.textContent=I[k].clip+' '+frameOf(k);
smalls[k].className=k==sel?'pcell on':'pcell';}}
// Timer-driven at the samples' rate (timers also run in a headless browser's virtual time).
function tick(){if(!playing)return;var now=performance.now();if(last&&NR>1){var span=(NR-1)*F.step/F.fps;t+=(now-last)/1000*speed/span;t-=Math.floor(t);}
last=now;render();setTimeout(tick,1000*F.step/F.fps);}
P.play=function(){if(playing)return;playing=true;last=0;pp.innerHTML='&#10074;&#10074; pause';tick();};
P.pause=function(){playing=false;pp.innerHTML='&#9654; play';render();};
P.select=function(k){sel=k;is.value=k;cmd.textContent='motifmine export '+data.archive+' --clip '+I[k].clip+' --start '+I[k].start+' --end '+I[k].end+' --out '+I[k].clip+'_'+I[k].start+'.bvh';render();};
P.state=function(){var w=[];for(var p=0;p<NP;p++)w.push(point(sel,p,true));return{instance:sel,clip:I[sel].clip,frame:frameOf(sel),label:lab.textContent,playing:playing,points:w,drawn:P.drawn,canvas:main};};
pp.onclick=function(){if(playing)P.pause();else P.play();};
scrub.oninput=function(){t=timeOfSample(sel,+scrub.value);render();};
sp.onchange=function(){speed=parseFloat(sp.value);};
hd.firstChild.onchange=function(){keep=hd.firstChild.checked;render();};
is.onchange=function(){P.select(parseInt(is.value,10));};
var drag=null;main.onmousedown=function(e){drag=[e.clientX,e.clientY];};
window.addEventListener('mouseup',function(){drag=null;});
main.onmousemove=function(e){if(!drag)return;yaw+=(e.clientX-drag[0])*0.01;pitch=Math.max(-1.2,Math.min(1.2,pitch+(e.clientY-drag[1])*0.01));drag=[e.clientX,e.clientY];render();};
P.select(0);}
document.addEventListener('click',function(e){var b=e.target.closest&&e.target.closest('button.play');if(!b)return;
var id=b.getAttribute('data-play');if(players[id])return;var d=document.getElementById('play-'+id);if(!d)return;
b.disabled=true;players[id]=new Player(b.parentNode,id,JSON.parse(d.textContent));});
})();
)js";

}  // namespace motif
