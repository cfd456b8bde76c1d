#include <cholmod.h>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>
using Clock=std::chrono::steady_clock;
double since(Clock::time_point t){return std::chrono::duration<double>(Clock::now()-t).count()*1e3;}
int main(int argc,char**argv){
  cholmod_common c; cholmod_start(&c);
  FILE*f=fopen(argv[1],"r"); cholmod_sparse*A=cholmod_read_sparse(f,&c); fclose(f);
  int n=A->nrow; printf("n=%d nnz=%ld stype=%d\n",n,(long)cholmod_nnz(A,&c),A->stype);
  for(int mode=0;mode<2;++mode){
    c.supernodal = mode==0? CHOLMOD_SUPERNODAL: CHOLMOD_SIMPLICIAL;
    c.final_ll = 0;
    auto t=Clock::now(); cholmod_factor*L=cholmod_analyze(A,&c); double ta=since(t);
    t=Clock::now(); for(int r=0;r<3;++r) cholmod_factorize(A,L,&c); double tf=since(t)/3;
    cholmod_dense*b=cholmod_ones(n,1,CHOLMOD_REAL,&c);
    t=Clock::now(); cholmod_dense*x=nullptr; for(int r=0;r<10;++r){ if(x) cholmod_free_dense(&x,&c); x=cholmod_solve(CHOLMOD_A,L,b,&c);} double ts=since(t)/10;
    printf("%s: analyze %.1f ms factorize %.1f ms solve %.2f ms lnz %.0f flops %.3g is_ll %d\n", mode==0?"supernodal":"simplicial",ta,tf,ts,c.lnz,c.fl,L->is_ll);
    if(mode==1){
      std::mt19937 g(1);
      int nb=n/6;
      for(int k: {1,2,10,50,200,600}){
        cholmod_sparse*C=cholmod_allocate_sparse(n,k,12*k,1,1,0,CHOLMOD_REAL,&c);
        int*p=(int*)C->p; int*ii=(int*)C->i; double*xx=(double*)C->x; int at=0;
        for(int j=0;j<k;++j){ p[j]=at; int b1=g()%nb; int b2=(b1+1+g()%5)%nb; if(b2<b1) std::swap(b1,b2); if(b1==b2) b2=(b1+1)%nb;
          for(int q=0;q<6;++q){ii[at]=6*b1+q; xx[at++]=1e5*(g()%100)/100.0;}
          for(int q=0;q<6;++q){ii[at]=6*b2+q; xx[at++]=1e5*(g()%100)/100.0;} }
        p[k]=at;
        cholmod_sort(C,&c);
        cholmod_sparse*Cp=cholmod_submatrix(C,(int*)L->Perm,n,nullptr,-1,1,1,&c); // permute rows
        t=Clock::now(); cholmod_updown(1,Cp,L,&c); double tu=since(t);
        t=Clock::now(); cholmod_updown(0,Cp,L,&c); double td=since(t);
        printf("  rank %d: update %.2f ms downdate %.2f ms\n",k,tu,td);
        cholmod_free_sparse(&C,&c); cholmod_free_sparse(&Cp,&c);
      }
    }
    cholmod_free_factor(&L,&c);
  }
  cholmod_finish(&c);
}
